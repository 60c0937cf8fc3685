#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/suite_runner.hpp"
#include "freeplay/results/run_folder.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

const SharedModels& models() { return SharedModels::shipped(); }

// Short free play (the children usually quit later) keeps these tests fast; the protocol stages are free.
Scenario test_scenario(const std::string& condition, const std::string& policy = "asocial", double cap_s = 240) {
  const std::string text = fmt::format(
      "name: t\ncondition: {}\nrobot: {{policy: {}}}\nprotocol: {{freeplay_cap_s: {}}}\n", condition, policy, cap_s);
  return scenario_from_document(parse_yaml(text, "test.yaml"));
}

}  // namespace

TEST(Episode, SameSeedGivesAnIdenticalEventLog) {
  const std::atomic<bool> stop{false};
  for (const auto* condition : {"child-child", "child-robot"}) {
    const auto s = test_scenario(condition);
    const auto a = run_episode({.scenario = s, .seed = 11, .models = models(), .stop = stop});
    const auto b = run_episode({.scenario = s, .seed = 11, .models = models(), .stop = stop});
    ASSERT_GT(a.events.size(), 20u) << condition;
    EXPECT_EQ(a.events.to_jsonl(), b.events.to_jsonl()) << condition;
    EXPECT_EQ(agents::to_pinsoro_yaml(a.annotations), agents::to_pinsoro_yaml(b.annotations));
    const auto c = run_episode({.scenario = s, .seed = 12, .models = models(), .stop = stop});
    EXPECT_NE(a.events.hash(), c.events.hash()) << condition;
  }
}

TEST(Episode, ChildRobotEpisodeFollowsTheProtocolAndRecordsMetrics) {
  const std::atomic<bool> stop{false};
  const auto r =
      run_episode({.scenario = test_scenario("child-robot", "asocial", 300), .seed = 5, .models = models(), .stop = stop});
  std::vector<std::string> stages;
  int moves = 0;
  for (const auto& e : r.events.events()) {
    if (e.type() == "stage") stages.push_back(e.data()["stage"]);
    if (e.source == "robot" && e.type() == "move_goal") ++moves;
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"greeting", "tutorial", "freeplay", "debriefing"}));
  EXPECT_GT(moves, 5);
  const auto& m = r.record["metrics"];
  EXPECT_TRUE(m.contains("label_share"));
  EXPECT_TRUE(m["label_share"]["purple"].contains("cooperative"));
  EXPECT_FALSE(m["label_share"].contains("yellow"));  // the robot takes the yellow place
  EXPECT_GT(m["robot_actions"]["move"].get<int>(), 0);
  EXPECT_TRUE(m["executor"].contains("sync_error_mm_mean"));
  EXPECT_LE(r.duration_s, 300.0);
  EXPECT_GT(r.simulated_s, r.duration_s + 300 + 90);  // greeting + tutorial + debriefing
  EXPECT_TRUE(r.annotations.purple.has_value());
  EXPECT_FALSE(r.annotations.yellow.has_value());
}

TEST(Episode, TheSocialPolicyNeverGrabsAnItemAChildHolds) {
  const std::atomic<bool> stop{false};
  int robot_grabs = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto r = run_episode(
        {.scenario = test_scenario("child-robot", "social", 400), .seed = seed, .models = models(), .stop = stop});
    for (const auto& e : r.events.events()) {
      if (e.type() != "item_grabbed" || e.data().value("holder", "") != "robot") continue;
      ++robot_grabs;
      EXPECT_TRUE(e.data()["shared_with"].empty()) << "seed " << seed << " t " << e.t << ": " << e.data().dump();
    }
  }
  EXPECT_GT(robot_grabs, 0);
}

TEST(Episode, StopFlagAbortsAnEpisode) {
  const std::atomic<bool> stop{true};
  EXPECT_TRUE(run_episode({.scenario = test_scenario("child-child"), .seed = 1, .models = models(), .stop = stop}).aborted);
}

TEST(Episode, OneAndTwoWorkersGiveIdenticalRunFolders) {
  const auto dir = std::filesystem::temp_directory_path() / "freeplay_test_episode_jobs";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  write_file_atomically(dir / "cc.yaml", "name: cc\ncondition: child-child\nepisodes: 3\nprotocol: {freeplay_cap_s: 120}\n");
  write_file_atomically(dir / "cr.yaml", "name: cr\ncondition: child-robot\nepisodes: 3\nprotocol: {freeplay_cap_s: 120}\n");
  write_file_atomically(dir / "s.yaml", "suite: s\nscenarios: [{scenario: cc.yaml}, {scenario: cr.yaml}]\n");
  const auto suite = load_suite(dir / "s.yaml");
  std::atomic<bool> stop{false};
  for (int jobs : {1, 2}) {
    RunOptions o;
    o.jobs = jobs;
    o.out = dir / fmt::format("jobs{}", jobs);
    o.progress = false;
    run_suite(suite, o, episode_function(models()), stop);
  }
  for (const char* file : {"events/cc-0002.jsonl", "events/cr-0001.jsonl", "annotations/cr-0002.yaml", "summary.csv"}) {
    EXPECT_EQ(read_file(dir / "jobs1" / file), read_file(dir / "jobs2" / file)) << file;
  }
  // episodes.jsonl differs only in the measured wall and planning times.
  auto strip = [](const std::filesystem::path& p) {
    std::string out;
    for (const auto& r : results::RunFolder(p).records()) {
      auto copy = r;
      copy.erase("wall_s");
      copy.erase("timing");
      out += copy.dump() + "\n";
    }
    return out;
  };
  EXPECT_EQ(strip(dir / "jobs1"), strip(dir / "jobs2"));
}
