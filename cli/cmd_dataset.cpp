// `freeplay dataset SUITE --out DIR`: a synthetic PInSoRo dataset: every episode of a suite recorded, its session
// folder laid out as the real dataset's `data/<YYYY-MM-DD-HHMMSSffffff>/` (docs/dataset.md). Resumable.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <ctime>
#include <fstream>
#include <iostream>
#include <map>

#include "command_registry.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/scenario/suite.hpp"
#include "freeplay/results/run_folder.hpp"
#include "run_command.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {
namespace {

constexpr std::int64_t kDatasetEpochS = 1500000000;  // the recordings' ROS epoch (recording::kEpochS)
constexpr std::int64_t kSessionSpacingS = 3600;      // one synthetic session per hour of the campaign

/// The real folder name of the `ordinal`-th session: its creation time `YYYY-MM-DD-HHMMSSffffff` (UTC).
std::string session_folder_name(std::int64_t ordinal) {
  const std::time_t t = kDatasetEpochS + ordinal * kSessionSpacingS;
  std::tm utc{};
  gmtime_r(&t, &utc);
  return fmt::format("{:04}-{:02}-{:02}-{:02}{:02}{:02}000000", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                     utc.tm_hour, utc.tm_min, utc.tm_sec);
}

/// Moves a session's camera videos (`video: true` cameras) to the real names `videos/camera_<c>_raw.<ext>`.
void move_videos(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (!std::filesystem::is_directory(from)) return;
  std::filesystem::create_directories(to);
  for (const auto& entry : std::filesystem::directory_iterator(from)) {
    const auto camera = entry.path().stem().string();
    const std::string real = camera == "env_camera" ? "camera_env" : camera;
    std::filesystem::rename(entry.path(), to / (real + "_raw" + entry.path().extension().string()));
  }
}

struct DatasetOptions {
  RunCommandOptions run;
};

void dataset_command(const DatasetOptions& o) {
  if (o.run.out.empty()) throw InputError("the dataset needs a folder", "--out", "a folder, e.g. --out pinsoro-sim");
  const std::filesystem::path root = o.run.out;
  auto run = o.run;
  run.out = (root / "run").string();
  run.record = true;
  run.no_summary = true;
  run_command(run, false);  // resumes the unfinished episodes; throws (exit 130) when interrupted

  // The suite's episodes in order: the n-th becomes data/<creation time of session n>/.
  std::vector<std::string> overrides = o.run.overrides;
  if (o.run.episodes) overrides.push_back(fmt::format("episodes={}", *o.run.episodes));
  if (o.run.seed) overrides.push_back(fmt::format("seed={}", *o.run.seed));
  const auto suite = scenario::is_suite_file(o.run.file) ? scenario::load_suite(o.run.file, overrides, scenario_vocabulary())
                                                       : scenario::single_scenario_suite(o.run.file, overrides,
                                                                                       scenario_vocabulary());
  std::map<std::string, nlohmann::json> records;
  {
    std::ifstream in(root / "run" / "episodes.jsonl");
    for (std::string line; std::getline(in, line);) {
      if (line.empty()) continue;
      auto r = nlohmann::json::parse(line);
      const auto id = r.value("episode_id", "");
      records[id] = std::move(r);
    }
  }
  const auto data = root / "data";
  std::filesystem::create_directories(data);
  std::string index = "session,episode_id,variant,condition,policy,seed,purple_age,yellow_age\n";
  std::int64_t ordinal = 0;
  int moved = 0;
  for (const auto& variant : suite.variants) {
    for (int i = 0; i < variant.scenario.episodes; ++i, ++ordinal) {
      const auto id = results::RunFolder::episode_file_id(variant.id, i);
      const auto name = session_folder_name(ordinal);
      const auto source = root / "run" / "sessions" / id;
      const auto target = data / name;
      if (!std::filesystem::exists(target / "freeplay.bag.md5") && std::filesystem::exists(source / "freeplay.bag.md5")) {
        std::filesystem::remove_all(target);
        std::filesystem::rename(source, target);
        move_videos(root / "run" / "videos" / id, target / "videos");
        ++moved;
      }
      const auto it = records.find(id);
      if (it == records.end()) continue;
      const auto& r = it->second;
      const auto children = r.value("children", nlohmann::json::object());
      auto age = [&](const char* seat) {
        return children.contains(seat) ? std::to_string(children[seat].value("age", 0)) : std::string();
      };
      index += fmt::format("{},{},{},{},{},{},{},{}\n", name, id, r.value("variant", ""), r.value("condition", ""),
                           r.value("policy", ""), r.value("seed", std::uint64_t{0}), age("purple"), age("yellow"));
    }
  }
  write_file_atomically(data / "sessions.csv", index);
  if (!o.run.quiet) {
    std::cerr << fmt::format("dataset: {} sessions in {} ({} laid out now); index {}\n", ordinal, data.string(), moved,
                             (data / "sessions.csv").string());
  }
}

const RegisterCommand dataset_registration(13, [](CLI::App& program) {
  auto o = std::make_shared<DatasetOptions>();
  auto* cmd = program.add_subcommand("dataset", "Generate a synthetic PInSoRo dataset (every episode of a suite, "
                                                "recorded, in the real folder layout)");
  cmd->add_option("file", o->run.file, "Suite (or scenario) YAML: conditions, policies, ages")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", o->run.out, "Dataset folder (data/<session>/ and the run it came from)")->required();
  cmd->add_option("--episodes", o->run.episodes, "Sessions per scenario (overrides the files)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--seed", o->run.seed, "Root seed of every scenario");
  cmd->add_option("-j,--jobs", o->run.jobs, "Parallel sessions (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->add_option("--set", o->run.overrides, "Override a scenario value, KEY.PATH=VALUE (repeatable)");
  cmd->add_flag("-q,--quiet", o->run.quiet, "No progress line");
  cmd->footer(
      "Each session: experiment.yaml, freeplay.bag (+ .yaml, .md5), freeplay.annotations.freeplay-sim.yaml, "
      "pinsoro-<id>.csv (+ .md5); data/sessions.csv indexes them. Ctrl-C keeps finished sessions; the same "
      "command resumes. Exit status: 0 done, 1 error, 2 bad input, 130 interrupted.");
  cmd->callback([o] { dataset_command(*o); });
});

}  // namespace
}  // namespace freeplay::cli
