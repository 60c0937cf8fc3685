// `freeplay run SCENARIO` and `freeplay suite SUITE`: run episodes headlessly, in parallel, resumably.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <csignal>
#include <iostream>
#include <sstream>
#include <thread>

#include "command_registry.hpp"
#include "episode_observers.hpp"
#include "run_command.hpp"
#include "sibling_program.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/results/run_folder.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {
namespace {

std::atomic<bool> g_stop{false};

extern "C" void on_interrupt(int /*signal*/) {
  if (g_stop.exchange(true)) std::_Exit(130);  // a second Ctrl-C quits at once
}

std::pair<int, int> parse_shard(const std::string& text) {
  int i = 0;
  int n = 0;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || !in.eof() || n < 1 || i < 1 || i > n) {
    throw InputError(fmt::format("'{}' is not a shard", text), "--shard", "I/N with 1 ≤ I ≤ N, e.g. 2/8");
  }
  return {i - 1, n};
}

nlohmann::json run_identity(const RunCommandOptions& o, const scenario::Suite& suite, std::pair<int, int> shard) {
  nlohmann::json variants = nlohmann::json::array();
  for (const auto& v : suite.variants) {
    variants.push_back({{"id", v.id}, {"episodes", v.scenario.episodes}, {"config_hash", v.scenario.config_hash}});
  }
  return {{"suite_file", std::filesystem::absolute(o.file).lexically_normal().string()},
          {"suite", suite.name},
          {"overrides", o.overrides},
          {"variants", variants},
          {"shard", {shard.first + 1, shard.second}}};
}

// The newest unfinished run folder under runs/ started by the same command (so re-running it resumes).
std::optional<std::filesystem::path> unfinished_run(const nlohmann::json& identity) {
  const std::filesystem::path runs("runs");
  if (!std::filesystem::is_directory(runs)) return std::nullopt;
  std::optional<std::filesystem::path> best;
  for (const auto& entry : std::filesystem::directory_iterator(runs)) {
    const auto meta = entry.path() / results::kRunManifestFile;
    if (!std::filesystem::exists(meta)) continue;
    try {
      auto j = nlohmann::json::parse(read_file(meta));
      if (j.value("complete", true)) continue;
      j.erase("complete");
      j.erase("title");
      if (j != identity) continue;
      if (!best || entry.path().filename() > best->filename()) best = entry.path();
    } catch (const std::exception&) {
    }
  }
  return best;
}

}  // namespace

void run_command(const RunCommandOptions& o, bool suite_command) {
  std::vector<std::string> overrides = o.overrides;
  if (o.episodes) overrides.push_back(fmt::format("episodes={}", *o.episodes));
  if (o.seed) overrides.push_back(fmt::format("seed={}", *o.seed));
  const auto shard = o.shard.empty() ? std::pair<int, int>{0, 1} : parse_shard(o.shard);
  const auto vocabulary = scenario_vocabulary();
  const bool is_suite = scenario::is_suite_file(o.file);
  if (suite_command && !is_suite) {
    throw InputError("this is a scenario file, not a suite (no top-level 'suite:' key)", "SUITE",
                     "a suite file; use `freeplay run` for a scenario", {o.file, 1, 1});
  }
  const auto suite = is_suite ? scenario::load_suite(o.file, overrides, vocabulary)
                              : scenario::single_scenario_suite(o.file, overrides, vocabulary);
  for (const auto& v : suite.variants) {  // e.g. a Python policy given to the C++ program: say so before starting
    if (v.scenario.condition == scenario::Condition::ChildRobot) policies::check_policy_available(v.scenario.robot.policy);
  }
  const ObserverOptions observer_options{o.record};
  if (!observers_available() && std::any_of(suite.variants.begin(), suite.variants.end(), [&](const auto& v) {
        return has_observers(v.scenario, observer_options);
      })) {
    // Recording or videos: the executable with the recorder and the camera rig runs the same command line.
    fail_with(exec_sibling_program("freeplay-full", program_arguments()));
  }
  RunCommandOptions effective = o;
  effective.overrides = overrides;
  const auto identity = run_identity(effective, suite, shard);

  std::filesystem::path out = o.out;
  if (out.empty()) {
    if (const auto previous = unfinished_run(identity)) {
      out = *previous;
      spdlog::info("resuming the unfinished run {} (same command); pass --out to start elsewhere", out.string());
    } else {
      out = results::RunFolder::default_dir(suite.name);
    }
  }
  std::filesystem::create_directories(out);
  const auto title = fmt::format("{} — {}", suite.name, suite.description);
  // run.json: what was run (resume and `freeplay merge` read it), the summary title, and whether it finished.
  auto write_run_json = [&](bool complete) {
    auto meta = identity;
    meta["title"] = title;
    meta["complete"] = complete;
    write_file_atomically(out / results::kRunManifestFile, meta.dump(2) + "\n");
  };
  write_run_json(false);

  const auto models = runner::SharedModels::load_default();
  runner::RunOptions options;
  options.jobs = std::max(1, o.jobs);
  options.out = out;
  options.progress = !o.quiet;
  options.shard_index = shard.first;
  options.shard_count = shard.second;
  options.title = title;
  options.events = runner::events_output_from_name(o.events);
  if (!o.quiet) {
    spdlog::info("{}: {} variant(s), {} episode(s){}, {} worker(s) → {}", suite.name, suite.variants.size(),
                 suite.total_episodes(),
                 shard.second > 1 ? fmt::format(" in the suite (shard {}/{})", shard.first + 1, shard.second) : "",
                 options.jobs, out.string());
  }

  g_stop.store(false);
  auto previous_handler = std::signal(SIGINT, on_interrupt);
  const auto report = runner::run_suite(suite, options, runner::episode_function(models, make_observer_factory(observer_options), out), g_stop);
  std::signal(SIGINT, previous_handler);

  const bool complete = report.skipped + report.finished >= report.total;
  write_run_json(complete);
  if (!o.quiet && !o.no_summary) std::cout << read_file(out / "summary.md");
  if (!complete) {
    std::cerr << fmt::format("interrupted: {} of {} episodes finished and kept in {}; run the same command again "
                             "to resume\n",
                             report.skipped + report.finished, report.total, out.string());
    fail_with(130);
  }
  if (!o.quiet) std::cerr << fmt::format("run folder: {}\n", out.string());
}

namespace {

void add_run_options(CLI::App* cmd, const std::shared_ptr<RunCommandOptions>& o, const char* what) {
  cmd->add_option("file", o->file, what)->required()->check(CLI::ExistingFile);
  cmd->add_option("--episodes", o->episodes, "Episodes per scenario (overrides the files)")->check(CLI::Range(1, 1000000));
  cmd->add_option("--seed", o->seed, "Root seed of every scenario (episode i uses a stream derived from it)");
  cmd->add_option("-j,--jobs", o->jobs, "Parallel episodes, one worker thread each (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("-o,--out", o->out,
                  "Run folder (default: runs/<UTC time>-<name>, or the unfinished run of the same command)");
  cmd->add_option("--set", o->overrides, "Override a scenario value, KEY.PATH=VALUE, validated like the file "
                                          "(repeatable), e.g. --set planner.name=rrtconnect");
  cmd->add_flag("-q,--quiet", o->quiet, "No progress line and no summary on the terminal");
  cmd->add_flag("--record", o->record, "Record every episode as a ROS bag session folder (as `record: true`)");
  cmd->add_option("--events", o->events,
                  "Event logs to keep: all (events/<episode>.jsonl), gz (.jsonl.gz), none, or auto (all up to 1000 "
                  "episodes in the run or shard, none above)")
      ->check(CLI::IsMember({"auto", "all", "gz", "none"}));
  cmd->footer(
      "Writes episodes.jsonl (one line per episode), events/<episode>.jsonl (see --events), "
      "annotations/<episode>.yaml "
      "(PInSoRo format), summary.csv and summary.md into the run folder. Ctrl-C stops cleanly: finished episodes "
      "are kept and summarised; the same command resumes. Exit status: 0 done, 1 error, 2 bad input, 130 "
      "interrupted.");
}

const RegisterCommand run_registration(10, [](CLI::App& program) {
  auto o = std::make_shared<RunCommandOptions>();
  auto* cmd = program.add_subcommand("run", "Run the episodes of one scenario and summarise them");
  add_run_options(cmd, o, "Scenario YAML file (see scenarios/)");
  cmd->callback([o] { run_command(*o, false); });
});

const RegisterCommand suite_registration(11, [](CLI::App& program) {
  auto o = std::make_shared<RunCommandOptions>();
  auto* cmd = program.add_subcommand("suite", "Run a suite of scenarios (with sweeps) and compare the conditions");
  add_run_options(cmd, o, "Suite YAML file, e.g. scenarios/baselines.yaml");
  cmd->add_option("--shard", o->shard, "Run only part I of N of the suite (for clusters; join with `freeplay merge`)");
  cmd->callback([o] { run_command(*o, true); });
});

}  // namespace
}  // namespace freeplay::cli
