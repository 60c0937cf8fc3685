// `freeplay replay SESSION_DIR`: reads a recorded session's bag back and recomputes its metrics, comparing them with
// the run's episodes.jsonl record when the session sits in a run folder; with --children-from-bag, re-runs the
// session with the recorded children's actions and a (new) robot policy into a run folder.
#ifdef FREEPLAY_WITH_RECORDING

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "command_registry.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/recording/child_replay.hpp"
#include "freeplay/recording/replay.hpp"
#include "freeplay/results/run_folder.hpp"
#include "vocabulary.hpp"

namespace freeplay::cli {
namespace {

struct ReplayOptions {
  std::string session;
  bool json = false;
  bool children_from_bag = false;
  std::string policy;
  std::string out;
};

// The episodes.jsonl record of a session folder `<run>/sessions/<id>`, if the run folder has one.
std::optional<nlohmann::json> episode_record(const std::filesystem::path& session) {
  const auto dir = std::filesystem::is_regular_file(session) ? session.parent_path() : session;
  const auto id = std::filesystem::absolute(dir).lexically_normal().filename().string();
  const auto jsonl = std::filesystem::absolute(dir).lexically_normal().parent_path().parent_path() / "episodes.jsonl";
  if (!std::filesystem::exists(jsonl)) return std::nullopt;
  std::istringstream lines(read_file(jsonl));
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    auto record = nlohmann::json::parse(line);
    if (record.value("episode_id", "") == id) return record;
  }
  return std::nullopt;
}

std::string number(double v) { return std::isnan(v) ? "nan" : fmt::format("{:.6g}", v); }

// --children-from-bag: a new episode with the recorded children, written to a run folder, metrics side by side.
void replay_children(const ReplayOptions& o) {
  const auto recorded = recording::read_recorded_children(o.session);
  const auto scenario = recording::replay_scenario(recorded, o.policy, scenario_vocabulary());
  const auto models = runner::SharedModels::load_default();
  auto result = recording::replay_children(recorded, scenario, models);
  const std::string variant = "replay";
  const auto id = results::RunFolder::episode_file_id(variant, 0);
  results::RunFolder folder(o.out.empty() ? results::RunFolder::default_dir("replay-" + recorded.episode_id)
                                         : std::filesystem::path(o.out));
  if (folder.finished(variant, 0, scenario.config_hash)) {
    throw InputError(fmt::format("'{}' already holds this replay", folder.dir().string()), "--out",
                     "another (or an empty) run folder");
  }
  folder.write("events/" + id + ".jsonl", result.events.to_jsonl());
  auto record = result.record;
  record["variant"] = variant;
  record["scenario"] = scenario.name;
  record["scenario_file"] = scenario.file;
  record["condition"] = std::string(scenario::to_string(scenario.condition));
  if (scenario.condition == scenario::Condition::ChildRobot) record["policy"] = scenario.robot.policy;
  record["episode"] = 0;
  record["episode_id"] = id;
  record["seed"] = recorded.seed;
  record["config_hash"] = scenario.config_hash;
  folder.append(record);

  auto before = episode_record(o.session);
  const auto before_metrics = recording::metric_values(
      before ? *before : recording::recompute_metrics(recording::read_session(o.session)));
  const auto after_metrics = recording::metric_values(record);
  if (o.json) {
    std::cout << nlohmann::json{{"run_folder", folder.dir().string()}, {"recorded", before_metrics},
                                {"replayed", after_metrics}}
                     .dump(2)
              << "\n";
    return;
  }
  std::cout << fmt::format("{}: children replayed from the bag ({:.1f} s of free play, ended by {}), robot policy '{}'\n",
                           recorded.bag.string(), recorded.freeplay_duration_s, recorded.ended_by,
                           scenario.condition == scenario::Condition::ChildRobot ? scenario.robot.policy : "-");
  std::cout << fmt::format("{:<52} {:>12} {:>12}\n", "metric", before ? "episodes.jsonl" : "from bag", "replayed");
  std::map<std::string, std::pair<double, double>> rows;
  for (const auto& [name, value] : before_metrics) rows[name] = {value, std::nan("")};
  for (const auto& [name, value] : after_metrics) {
    rows.try_emplace(name, std::nan(""), value);
    rows[name].second = value;
  }
  for (const auto& [name, values] : rows) {
    if (name.rfind("metrics.label_share", 0) == 0) continue;  // replayed children have no annotations
    std::cout << fmt::format("{:<52} {:>12} {:>12}\n", name, number(values.first), number(values.second));
  }
  std::cout << fmt::format("run folder: {} (no annotations: the replayed children's states are unknown)\n",
                           folder.dir().string());
}

void replay(const ReplayOptions& o) {
  if (o.children_from_bag) {
    replay_children(o);
    return;
  }
  if (!o.policy.empty() || !o.out.empty()) {
    throw InputError("--policy and --out need --children-from-bag", o.policy.empty() ? "--out" : "--policy",
                     "add --children-from-bag, or omit them (metric recomputation only)");
  }
  const auto recording = recording::read_session(o.session);
  const auto recomputed = recording::recompute_metrics(recording);
  const auto record = episode_record(o.session);
  std::vector<recording::MetricComparison> comparison;
  if (record) comparison = recording::compare_with_record(recomputed, *record);
  int differing = 0;
  for (const auto& c : comparison) differing += c.equal ? 0 : 1;
  if (o.json) {
    nlohmann::json out = recomputed;
    out["bag"] = recording.bag.string();
    out["topics"] = recording.topic_counts;
    if (record) {
      out["compared_with_episodes_jsonl"] = comparison.size();
      out["differing"] = differing;
    }
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << fmt::format("{}: {:.1f} s recorded, {} topics, {} events{}\n", recording.bag.string(),
                             recording.end_s - recording.start_s, recording.topic_counts.size(), recording.events.size(),
                             recomputed["extra"]["complete"].get<bool>() ? "" : " (INCOMPLETE recording)");
    const auto replayed = recording::metric_values(recomputed);
    std::map<std::string, const recording::MetricComparison*> by_name;
    for (const auto& c : comparison) by_name[c.name] = &c;
    std::cout << fmt::format("{:<52} {:>12} {:>12}  {}\n", "metric", "from bag", "episodes.jsonl", "");
    auto row = [&](const std::string& name, double value) {
      const auto it = by_name.find(name);
      std::cout << fmt::format("{:<52} {:>12} {:>12}  {}\n", name, number(value),
                               it != by_name.end() ? number(it->second->recorded) : "-",
                               it == by_name.end() ? "" : it->second->equal ? "=" : "DIFFERS");
    };
    row("duration_s", recomputed.value("duration_s", std::nan("")));
    for (const auto& [name, value] : replayed) row(name, value);
    for (const auto& c : comparison) {  // in the record, but the bag does not hold what it needs (an older session)
      if (c.name != "duration_s" && !replayed.contains(c.name)) {
        std::cout << fmt::format("{:<52} {:>12} {:>12}  {}\n", c.name, "-", number(c.recorded), "NOT IN BAG");
      }
    }
    for (const auto& [message, count] : recomputed["extra"]["interaction_events"].items()) {
      std::cout << fmt::format("{:<52} {:>12}\n", "interaction_events." + message, count.get<int>());
    }
    if (record) {
      std::cout << fmt::format("{} of {} metrics identical to episodes.jsonl\n", comparison.size() - differing,
                               comparison.size());
    } else {
      std::cout << "(no episodes.jsonl record next to the session: nothing compared)\n";
    }
  }
  if (differing > 0) fail_with(1);
}

const RegisterCommand replay_command(45, [](CLI::App& program) {
  auto o = std::make_shared<ReplayOptions>();
  auto* cmd = program.add_subcommand("replay", "Recompute an episode's metrics from its recorded ROS bag");
  cmd->add_option("session", o->session, "Session folder (<run>/sessions/<episode id>) or a .bag file")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_flag("--json", o->json, "Print JSON instead of a table");
  cmd->add_flag("--children-from-bag", o->children_from_bag,
                "Re-run the session with the children's actions replayed from the bag while a robot policy plays");
  cmd->add_option("--policy", o->policy, "Robot policy for --children-from-bag (default: the recorded one)");
  cmd->add_option("-o,--out", o->out, "Run folder for --children-from-bag (default: runs/<UTC time>-replay-<id>)");
  cmd->footer("Exit status: 0 when every metric equals the run's episodes.jsonl record (or there is none), 1 when\n"
              "any differs, 2 on bad input (no bag, an unindexed bag: run `rosbag reindex`). With\n"
              "--children-from-bag: writes episodes.jsonl and events/ of the new episode into the run folder and\n"
              "prints its metrics beside the recorded ones (exit 0).");
  cmd->callback([o] { replay(*o); });
});

}  // namespace
}  // namespace freeplay::cli

#endif  // FREEPLAY_WITH_RECORDING
