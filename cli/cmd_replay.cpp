// `freeplay replay SESSION_DIR`: reads a recorded session's bag back and recomputes its metrics, comparing them with
// the run's episodes.jsonl record when the session sits in a run folder.
#ifdef FREEPLAY_WITH_RECORDING

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "command_registry.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/recording/replay.hpp"

namespace freeplay::cli {
namespace {

struct ReplayOptions {
  std::string session;
  bool json = false;
  bool children_from_bag = false;
  std::string policy;
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

void replay(const ReplayOptions& o) {
  if (o.children_from_bag) {
    throw InputError("--children-from-bag is not implemented yet", "--children-from-bag",
                     "omit it (metric recomputation only)");
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
    const auto replayed = recording::flatten_numbers(recomputed.value("metrics", nlohmann::json::object()), "metrics");
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
                "Re-run the session with the children's touches replayed from the bag (not implemented yet)");
  cmd->add_option("--policy", o->policy, "Robot policy for --children-from-bag");
  cmd->footer("Exit status: 0 when every metric equals the run's episodes.jsonl record (or there is none), 1 when\n"
              "any differs, 2 on bad input (no bag, an unindexed bag: run `rosbag reindex`).");
  cmd->callback([o] { replay(*o); });
});

}  // namespace
}  // namespace freeplay::cli

#endif  // FREEPLAY_WITH_RECORDING
