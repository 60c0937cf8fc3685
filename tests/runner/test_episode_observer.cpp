#include <fmt/format.h>
#include <gtest/gtest.h>

#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

const SharedModels& models() { return SharedModels::shipped(); }

Scenario short_scenario(const std::string& condition) {
  const std::string text = fmt::format(
      "name: t\ncondition: {}\nprotocol: {{greeting_s: 12.05, tutorial_s: 5, freeplay_cap_s: 60, debriefing_s: 3}}\n",
      condition);
  return scenario_from_document(parse_yaml(text, "test.yaml"));
}

// Remembers what it saw.
struct RecordingObserver final : EpisodeObserver {
  int begun = 0, ended = 0, aborted = 0;
  std::vector<double> times;
  std::vector<std::string> stages;
  std::size_t events_seen = 0;
  bool robot_seen = false;
  std::size_t robot_joints = 0;
  std::size_t children = 0;
  void begin(const EpisodeInfo& info) override {
    ++begun;
    EXPECT_EQ(info.id, "t-0");
  }
  void observe(const EpisodeSnapshot& s) override {
    times.push_back(s.t);
    if (stages.empty() || stages.back() != s.stage) stages.emplace_back(s.stage);
    events_seen += s.new_events.size();
    ASSERT_NE(s.tray, nullptr);
    EXPECT_NEAR(s.tray->time(), s.t, 1e-9);
    children = s.children.size();
    if (s.robot != nullptr) {
      robot_seen = true;
      robot_joints = s.robot->joint_names.size();
      EXPECT_EQ(s.robot->positions.size(), robot_joints);
    }
  }
  void end(EpisodeResult& result) override {
    ++ended;
    result.record["observed"] = true;
  }
  void abort() override { ++aborted; }
};

}  // namespace

TEST(EpisodeObserver, SeesEveryTickOfEveryStageWithoutChangingTheEpisode) {
  const std::atomic<bool> stop{false};
  for (const auto* condition : {"child-child", "child-robot"}) {
    const auto s = short_scenario(condition);
    const auto plain = run_episode({.scenario = s, .seed = 5, .models = models(), .stop = stop});
    EpisodeObservers observers;
    observers.push_back(std::make_unique<RecordingObserver>());
    auto* seen = static_cast<RecordingObserver*>(observers.back().get());
    const auto observed =
        run_episode({.scenario = s, .seed = 5, .models = models(), .stop = stop, .id = "t-0"}, observed_by(observers));
    EXPECT_EQ(plain.events.to_jsonl(), observed.events.to_jsonl()) << condition;
    EXPECT_EQ(observed.record.value("observed", false), true);
    EXPECT_EQ(seen->begun, 1);
    EXPECT_EQ(seen->ended, 1);
    EXPECT_EQ(seen->aborted, 0);
    EXPECT_EQ(seen->stages, (std::vector<std::string>{"greeting", "tutorial", "freeplay", "debriefing"}));
    EXPECT_EQ(seen->events_seen, observed.events.size()) << "every event is handed over once";
    ASSERT_GT(seen->times.size(), 100u);
    for (std::size_t i = 1; i < seen->times.size(); ++i) {
      EXPECT_LE(seen->times[i] - seen->times[i - 1], 0.1 + 1e-9) << "10 Hz ticks at " << seen->times[i];
      EXPECT_GT(seen->times[i], seen->times[i - 1]);
    }
    EXPECT_EQ(seen->robot_seen, std::string(condition) == "child-robot");
    if (seen->robot_seen) {
      EXPECT_EQ(seen->robot_joints, 26u);
    }
    EXPECT_EQ(seen->children, std::string(condition) == "child-robot" ? 1u : 2u);
  }
}

TEST(EpisodeObserver, IsToldWhenTheEpisodeStops) {
  const std::atomic<bool> stop{true};
  const auto s = short_scenario("child-robot");
  EpisodeObservers observers;
  observers.push_back(std::make_unique<RecordingObserver>());
  auto* seen = static_cast<RecordingObserver*>(observers.back().get());
  const auto result =
      run_episode({.scenario = s, .seed = 5, .models = models(), .stop = stop, .id = "t-0"}, observed_by(observers));
  EXPECT_TRUE(result.aborted);
  EXPECT_EQ(seen->aborted, 1);
  EXPECT_EQ(seen->ended, 0);
}
