// The yoked control end to end: a yoked run replays the source run's robot actions (content and free-play time),
// each episode those of another child's session, deterministically and whatever the number of workers; a source it cannot replay is refused
// before any episode starts.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/scenario/suite.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/results/run_folder.hpp"
#include "../scratch_dir.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;
namespace fs = std::filesystem;

namespace {

constexpr int kEpisodes = 3;

/// A scratch folder for this file's test `name`.
std::filesystem::path fresh_dir(const std::string& name) { return test_support::fresh_dir("yoked-" + name); }

/// A short child-robot scenario file with `policy` and `params` (YAML flow map).
fs::path scenario_file(const fs::path& dir, const std::string& name, const std::string& policy,
                       const std::string& params = "{}", int episodes = kEpisodes) {
  const auto path = dir / (name + ".yaml");
  write_file_atomically(path, fmt::format("name: {}\ncondition: child-robot\nepisodes: {}\nseed: 11\n"
                                          "robot: {{policy: {}, params: {}}}\n"
                                          "protocol: {{greeting_s: 5, tutorial_s: 5, freeplay_cap_s: 300, "
                                          "debriefing_s: 1}}\n",
                                          name, episodes, policy, params));
  return path;
}

void run(const fs::path& scenario, const fs::path& out, int jobs, EventsOutput events = EventsOutput::All) {
  RunOptions o;
  o.jobs = jobs;
  o.out = out;
  o.progress = false;
  o.events = events;
  std::atomic<bool> stop{false};
  ScenarioVocabulary registered;  // the default vocabulary predates `yoked`: take the registry's names
  registered.policies = policies::policy_names();
  run_suite(single_scenario_suite(scenario, {}, registered), o, episode_function(SharedModels::shipped()), stop);
}

/// The robot's actions of one event log as "free-play t | type | data" lines, up to free-play time `until`
/// (the item a gaze point falls on depends on where this child left the items: left out).
std::vector<std::string> robot_actions(const fs::path& log, double until) {
  std::vector<std::string> out;
  std::optional<double> start;
  std::istringstream lines(read_file(log));
  std::string line;
  while (std::getline(lines, line)) {
    const auto e = nlohmann::json::parse(line);
    if (e["type"] == "stage") {
      if (e["data"]["stage"] == "freeplay") start = e["t"].get<double>();
      if (e["data"]["stage"] == "debriefing") break;
      continue;
    }
    if (!start || e["source"] != "robot" || e["type"] == "move_result") continue;
    const double t = e["t"].get<double>() - *start;
    if (t > until + 1e-6) break;
    auto data = e["data"];
    if (data.is_object()) data.erase("item");
    if (e["type"] == "move_goal") data["item"] = e["data"]["item"];
    out.push_back(fmt::format("{:.1f} | {} | {}", t, e["type"].get<std::string>(), data.dump()));
  }
  return out;
}

/// The free-play duration of each episode of a run folder, by index.
std::vector<double> durations(const fs::path& dir) {
  std::vector<double> out(kEpisodes, 0.0);
  for (const auto& r : results::RunFolder(dir).records())
    out[r["episode"].get<std::size_t>()] = r["duration_s"].get<double>();
  return out;
}

}  // namespace

TEST(YokedReplay, ReplaysTheSourcesRobotActionsOfAnotherChild) {
  const auto dir = fresh_dir("replay");
  for (const std::string source : {"social", "asocial"}) {
    run(scenario_file(dir, source, source), dir / source, 2);
    const auto yoked = scenario_file(dir, "yoked-" + source, "yoked", fmt::format("{{from: '{}'}}", (dir / source).string()));
    run(yoked, dir / ("yoked-" + source), 2);
    const auto yoked_durations = durations(dir / ("yoked-" + source));
    std::size_t compared = 0;
    for (int k = 0; k < kEpisodes; ++k) {
      // Episode k replays source episode k + 1 (mod 3): the session of another child, over the free play both
      // episodes had (after the source's end the yoked robot does nothing).
      const auto source_log = dir / source / "events" / fmt::format("{}-{:04d}.jsonl", source, (k + 1) % kEpisodes);
      const auto expected = robot_actions(source_log, yoked_durations[static_cast<std::size_t>(k)]);
      const auto replayed =
          robot_actions(dir / ("yoked-" + source) / "events" / fmt::format("yoked-{}-{:04d}.jsonl", source, k), 1e9);
      EXPECT_EQ(replayed, expected) << source << " episode " << k;
      compared += expected.size();
    }
    EXPECT_GT(compared, 10u) << source;  // the sources really acted
  }
}

TEST(YokedReplay, OffsetZeroReproducesTheSourceSessionsExactly) {
  // The same child (same seed) and the same robot actions at the same times: the same session. This is why the
  // default offset is 1 (docs/validity.md).
  const auto dir = fresh_dir("offset0");
  run(scenario_file(dir, "social", "social"), dir / "social", 2);
  run(scenario_file(dir, "same", "yoked", fmt::format("{{from: '{}', episode_offset: 0}}", (dir / "social").string())),
      dir / "same", 2);
  EXPECT_EQ(durations(dir / "same"), durations(dir / "social"));
  for (int k = 0; k < kEpisodes; ++k) {
    EXPECT_EQ(robot_actions(dir / "same" / "events" / fmt::format("same-{:04d}.jsonl", k), 1e9),
              robot_actions(dir / "social" / "events" / fmt::format("social-{:04d}.jsonl", k), 1e9));
  }
}

TEST(YokedReplay, IsDeterministicAndJobsInvariant) {
  const auto dir = fresh_dir("jobs");
  run(scenario_file(dir, "social", "social"), dir / "social", 2);
  const auto yoked = scenario_file(dir, "yoked", "yoked", fmt::format("{{from: '{}'}}", (dir / "social").string()));
  run(yoked, dir / "jobs1", 1);
  run(yoked, dir / "jobs2", 2);
  for (int k = 0; k < kEpisodes; ++k) {
    const auto file = fmt::format("events/yoked-{:04d}.jsonl", k);
    EXPECT_EQ(read_file(dir / "jobs1" / file), read_file(dir / "jobs2" / file)) << file;
  }
}

TEST(YokedReplay, ASourceItCannotReplayIsRefusedBeforeAnyEpisode) {
  const auto dir = fresh_dir("refused");
  run(scenario_file(dir, "social", "social", "{}", 2), dir / "social", 2);
  run(scenario_file(dir, "quiet", "social", "{}", 2), dir / "quiet", 2, EventsOutput::None);
  const auto from = [&](const char* run) { return fmt::format("{{from: '{}'}}", (dir / run).string()); };
  try {
    run(scenario_file(dir, "more", "yoked", from("social"), 3), dir / "more", 1);
    FAIL() << "three episodes yoked to two";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds 2 episodes, this run has 3"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "more" / "episodes.jsonl") && !read_file(dir / "more" / "episodes.jsonl").empty());
  try {
    run(scenario_file(dir, "none", "yoked", from("quiet"), 2), dir / "none", 1);
    FAIL() << "a source without event logs";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--events all"), std::string::npos) << e.what();
  }
}
