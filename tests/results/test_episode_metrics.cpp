// The metrics unit on hand-made event sequences: each metric's arithmetic, independent of the episode loop.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "freeplay/results/episode_metrics.hpp"

namespace freeplay::results {
namespace {

/// Items at set positions; one zone "blue" for x < 0.5.
class FakeWorld final : public MetricsWorld {
 public:
  std::map<std::string, Vec2> items;
  Vec2 item_position(const std::string& item) const override { return items.at(item); }
  std::string zone_at(const Vec2& p) const override { return p.x() < 0.5 ? "blue" : ""; }
};

// The metrics read typed events (core/events.hpp): the tests build the structs the emitters build.
struct Feeder {
  EpisodeMetrics metrics;
  FakeWorld world;
  explicit Feeder(bool child_robot) : metrics(child_robot) {
    feed(10.0, {10.0, "protocol", "stage", {{"stage", "freeplay"}}});
  }
  void feed(double tick, const Event& e) { metrics.observe(e, tick, world); }
};

TEST(EpisodeMetrics, CountsTouchesMovesZoneTransitionsAndIgnoresNudges) {
  Feeder f(false);
  f.feed(10.1, {10.05, "child.purple", events::TouchDown{1, 0.2, -0.3, "item"}});
  f.feed(10.1, {10.05, "child.yellow", events::TouchDown{4, 0.8, -0.3, "item"}});
  f.world.items["zebra"] = {0.2, -0.3};
  f.feed(10.1, {10.05, "sandtray", events::ItemGrabbed{"zebra", 1, {}}});
  f.world.items["zebra"] = {0.8, -0.3};  // moved out of the blue zone
  f.feed(10.5, {10.45, "sandtray", events::ItemReleased{"zebra", 1, "touch_up"}});
  f.feed(10.6, {10.55, "sandtray", events::ItemGrabbed{"zebra", 4, {}}});
  f.world.items["zebra"] = {0.81, -0.3};  // 1 cm: not a move
  f.feed(10.7, {10.65, "sandtray", events::ItemReleased{"zebra", 4, "touch_up"}});
  const auto m = f.metrics.to_json(60.0, {}, 0.25);
  EXPECT_EQ(m["child"]["purple"]["touches_per_min"].get<double>(), 1.0);
  EXPECT_EQ(m["child"]["yellow"]["touches_per_min"].get<double>(), 1.0);
  EXPECT_EQ(m["child"]["purple"]["item_moves_per_min"].get<double>(), 1.0);
  EXPECT_EQ(m["child"]["yellow"]["item_moves_per_min"].get<double>(), 0.0);
  EXPECT_EQ(m["child_touches_per_min"].get<double>(), 2.0);
  EXPECT_EQ(m["zone_transitions"].get<int>(), 1);
  EXPECT_EQ(m["drawing_coverage"].get<double>(), 0.25);
  EXPECT_FALSE(m.contains("robot_actions"));
}

TEST(EpisodeMetrics, MutualGazeAndJointAttentionPerTick) {
  Feeder f(false);
  f.feed(10.1, {10.05, "child.purple", "gaze", {{"target", "partner"}}});
  f.feed(10.1, {10.05, "child.yellow", "gaze", {{"target", "partner"}}});
  f.metrics.measure_gaze();
  f.metrics.measure_gaze();
  f.feed(10.3, {10.25, "child.purple", "gaze", {{"target", "item"}, {"item", "zebra"}}});
  f.feed(10.3, {10.25, "child.yellow", "gaze", {{"target", "item"}, {"item", "zebra"}}});
  f.metrics.measure_gaze();
  f.metrics.measure_gaze();  // still the same joint-attention episode
  f.feed(10.5, {10.45, "child.yellow", "gaze", {{"target", "item"}, {"item", "lion"}}});
  f.metrics.measure_gaze();
  f.feed(10.6, {10.55, "child.yellow", "gaze", {{"target", "item"}, {"item", "zebra"}}});
  f.metrics.measure_gaze();
  const auto m = f.metrics.to_json(60.0, {}, 0.0);
  EXPECT_DOUBLE_EQ(m["mutual_gaze_s"].get<double>(), 0.2);
  EXPECT_EQ(m["joint_attention_episodes"].get<int>(), 2);
}

TEST(EpisodeMetrics, RobotActionsLatencyPlannerExecutorAndPlacement) {
  Feeder f(true);
  f.world.items["zebra"] = {0.2, -0.3};
  f.feed(11.0, {10.95, "sandtray", events::ItemGrabbed{"zebra", 2, {}}});
  f.world.items["zebra"] = {0.3, -0.3};
  f.feed(11.0, {10.95, "sandtray", events::ItemReleased{"zebra", 2, "touch_up"}});  // child move at t = 1.0
  // Decided in the loop's tick t = 1.5 (seen in the snapshot after it, 11.6).
  f.feed(11.6, {11.5, "robot", "move_goal", {{"item", "zebra"}, {"x", 0.5}, {"y", -0.3}}});
  f.feed(12.0, {11.9, "sandtray", events::ItemGrabbed{"zebra", std::nullopt, {}}});
  f.feed(13.0, {12.9, "robot", "move_result",
                {{"item", "zebra"}, {"status", "succeeded"}, {"path_length_m", 0.2}, {"min_clearance_mm", 30.0},
                 {"sync_error_mm_mean", 4.0}, {"sync_error_mm_max", 9.0}, {"sync_lag_ms", 100.0},
                 {"duration_s", 1.5}, {"stolen_by_child", false}}});
  f.world.items["zebra"] = {0.503, -0.304};
  f.feed(13.1, {13.05, "sandtray", "interaction_event", {{"message", "releasing_zebra"}}});
  f.feed(13.1, {13.05, "sandtray", events::ItemReleased{"zebra", std::nullopt, "timeout"}});
  f.feed(13.3, {13.2, "robot", "look_at", {{"child", "purple"}}});
  f.feed(13.3, {13.2, "robot", "move_goal", {{"item", "lion"}, {"x", 0.1}, {"y", -0.1}}});
  f.feed(13.4, {13.3, "robot", "move_result", {{"item", "lion"}, {"status", "aborted"}, {"stolen_by_child", true}}});
  f.feed(13.4, {13.3, "robot", events::Say{"oh", "", 0.5}});
  f.feed(13.5, {13.5, "protocol", "stage", {{"stage", "debriefing"}}});
  f.feed(13.6, {13.5, "robot", events::Say{"bye", "", 0.5}});  // after free play: not an action
  const auto m = f.metrics.to_json(120.0, {}, 0.0);
  EXPECT_EQ(m["robot_actions"]["move"].get<int>(), 2);
  EXPECT_EQ(m["robot_actions"]["look"].get<int>(), 1);
  EXPECT_EQ(m["robot_actions"]["say"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(m["robot_actions_per_min"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(m["robot_response_latency_s"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(m["robot_item_moves_per_min"].get<double>(), 0.5);
  EXPECT_EQ(m["items_taken_by_robot_from_child"].get<int>(), 1);  // the child moved it 2 s before
  EXPECT_EQ(m["planner"]["moves_started"].get<int>(), 2);
  EXPECT_DOUBLE_EQ(m["planner"]["success_rate"].get<double>(), 0.5);
  EXPECT_EQ(m["planner"]["moves_failed"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(m["planner"]["path_length_m"].get<double>(), 0.2);
  EXPECT_EQ(m["executor"]["moves_stolen_by_child"].get<int>(), 1);
  EXPECT_NEAR(m["executor"]["placement_error_mm"].get<double>(), 5.0, 1e-9);
  EXPECT_DOUBLE_EQ(m["executor"]["sync_error_mm_max"].get<double>(), 9.0);
}

TEST(EpisodeMetrics, ObserveNewFeedsEachLogEntryOnce) {
  EpisodeMetrics once(false);
  FakeWorld world;
  EventLog log;
  log.emit({0.0, "protocol", "stage", {{"stage", "freeplay"}}});
  log.emit({0.05, "child.purple", events::TouchDown{1, 0.2, -0.3, "stroke"}});
  once.observe_new(log, 0.1, world);
  once.observe_new(log, 0.2, world);
  log.emit({0.25, "child.purple", events::TouchDown{2, 0.4, -0.3, "stroke"}});
  once.observe_new(log, 0.3, world);
  EXPECT_EQ(once.to_json(60.0, {}, 0.0)["child"]["purple"]["touches_per_min"].get<double>(), 2.0);
}

}  // namespace
}  // namespace freeplay::results
