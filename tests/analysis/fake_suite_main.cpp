// A stand-in for `freeplay suite SUITE [--shard I/N] --out DIR [--jobs J] [--quiet] [--set K=V]…` for the Slurm
// test while the episode loop is not in this build: the real suite loader, runner (sharding, resume, run folder,
// summaries) and a run.json like the CLI's, with synthetic episodes that depend only on their seed.

#include <fmt/format.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/scenario/suite.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/results/run_folder.hpp"

namespace {

using namespace freeplay;

runner::EpisodeOutput synthetic_episode(const runner::EpisodeTask& task, std::atomic<int>& counter) {
  Rng rng(task.seed ^ fnv1a64(task.variant->id));
  const double cap = task.variant->scenario.protocol.freeplay_cap_s;
  runner::EpisodeOutput out;
  out.record["duration_s"] = cap * rng.uniform(0.2, 1.0);
  out.record["ended_by"] = "quit";
  out.record["simulated_s"] = cap;
  out.record["wall_s"] = 0.001 * counter.fetch_add(1);  // differs between runs, like a clock
  out.record["metrics"]["robot_item_moves_per_min"] = rng.normal(2.0, 0.5);
  out.record["metrics"]["label_share"]["purple"]["cooperative"] = rng.uniform();
  const auto id = results::RunFolder::episode_file_id(task.variant->id, task.index);
  out.files["events/" + id + ".jsonl"] = fmt::format("{{\"t\":0,\"seed\":{}}}\n", task.seed);
  out.simulated_s = cap;
  return out;
}

int run(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] != "suite" || args.size() < 2) {
    std::cerr << "usage: fake_suite suite SUITE [--shard I/N] --out DIR [--jobs J] [--quiet] [--set K=V]…\n";
    return 2;
  }
  const std::string suite_file = args[1];
  runner::RunOptions options;
  options.progress = false;
  std::vector<std::string> overrides;
  int shard_index = 1;
  for (std::size_t i = 2; i < args.size(); ++i) {
    const auto next = [&]() -> std::string {
      if (i + 1 >= args.size()) throw InputError("missing value", args[i]);
      return args[++i];
    };
    if (args[i] == "--shard") {
      const auto value = next();
      if (std::sscanf(value.c_str(), "%d/%d", &shard_index, &options.shard_count) != 2) {
        throw InputError("bad shard", "--shard", "I/N");
      }
      options.shard_index = shard_index - 1;
    } else if (args[i] == "--out") {
      options.out = next();
    } else if (args[i] == "--jobs") {
      options.jobs = std::stoi(next());
    } else if (args[i] == "--set") {
      overrides.push_back(next());
    } else if (args[i] != "--quiet") {
      throw InputError("unknown option", args[i]);
    }
  }
  const auto suite = scenario::load_suite(suite_file, overrides);
  std::atomic<int> counter{0};
  std::atomic<bool> stop{false};
  runner::run_suite(
      suite, options,
      [&](const runner::EpisodeTask& task, const std::atomic<bool>&) { return synthetic_episode(task, counter); },
      stop);
  nlohmann::json manifest{{"suite_file", suite_file}, {"suite", suite.name}, {"overrides", overrides},
                          {"shard", {shard_index, options.shard_count}}};
  for (const auto& v : suite.variants) manifest["variants"].push_back({{"id", v.id}, {"episodes", v.scenario.episodes}});
  std::ofstream(options.out / "run.json") << manifest.dump(2) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
}
