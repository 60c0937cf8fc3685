// The planner's settings: the one home of its defaults, and what a scenario's `planner:` block makes of them.

#include <gtest/gtest.h>

#include "freeplay/planning/move_executor.hpp"
#include "freeplay/planning/plan.hpp"
#include "freeplay/planning/planner_settings.hpp"
#include "test_helpers.hpp"

namespace freeplay::planning {
namespace {

TEST(PlannerSettings, EveryStructStartsFromTheSettingsDefaults) {
  const PlannerSettings defaults;
  EXPECT_EQ(defaults.name, "astar");
  EXPECT_EQ(PlanRequest{}.time_budget_s, defaults.time_budget_s);
  EXPECT_EQ(MoveExecutorConfig{}.time_budget_s, defaults.time_budget_s);
  EXPECT_EQ(PlannerOptions{}.finger_speed_mps, defaults.finger_speed_mps);
  EXPECT_EQ(PlannerOptions{}.pose_period_s, MoveExecutorConfig{}.pose_period_s);
  // The one home of each default: the named constants the settings start from.
  EXPECT_EQ(defaults.time_budget_s, kDefaultTimeBudgetS);
  EXPECT_EQ(defaults.finger_speed_mps, kDefaultFingerSpeedMps);
  // A scenario that leaves `planner:` out gives its executor and its planners the same defaults.
  const MoveExecutorConfig from_defaults = move_executor_config(defaults);
  EXPECT_EQ(from_defaults.time_budget_s, PlanRequest{}.time_budget_s);
  ASSERT_TRUE(from_defaults.finger_speed_mps.has_value());
  EXPECT_EQ(*from_defaults.finger_speed_mps, PlannerOptions{}.finger_speed_mps);
  EXPECT_EQ(planner_options(defaults).finger_speed_mps, PlannerOptions{}.finger_speed_mps);
  EXPECT_EQ(make_planner(defaults)->name(), defaults.name);
}

TEST(PlannerSettings, ExecutorConfigTakesTheBudgetAndTheFingerSpeed) {
  PlannerSettings settings;
  settings.time_budget_s = 2.5;
  settings.finger_speed_mps = 0.08;
  const MoveExecutorConfig config = move_executor_config(settings);
  EXPECT_EQ(config.time_budget_s, 2.5);
  ASSERT_TRUE(config.finger_speed_mps.has_value());
  EXPECT_EQ(*config.finger_speed_mps, 0.08);
  EXPECT_EQ(config.exact_endpoints, MoveExecutorConfig{}.exact_endpoints);
}

TEST(PlannerSettings, BlockedGoalsAreRefusedOnlyWhenAsked) {
  const std::vector<Obstacle> rock = {testing::box("rock", 0.2, 0.3, -0.2, -0.1)};
  PlanRequest request;
  request.item = "mover";
  request.start = {0.1, -0.05};
  request.goal = {0.25, -0.15};  // inside the rock
  request.obstacles = rock;
  PlannerSettings settings;
  EXPECT_GT(planner_options(settings).goal_blocked_occupancy, 100);  // the real planner: any point
  Rng rng(5);
  const PlanResult through = make_planner(settings)->plan(request, rng);
  EXPECT_TRUE(through.ok) << through.message;
  settings.reject_blocked_goals = true;
  EXPECT_EQ(planner_options(settings).goal_blocked_occupancy, PlannerOptions{}.goal_blocked_occupancy);
  EXPECT_EQ(make_planner(settings)->plan(request, rng).reason, FailureReason::GoalInsideObstacle);
  settings.name = "rrtconnect";
  EXPECT_EQ(make_planner(settings)->name(), "rrtconnect");
}

}  // namespace
}  // namespace freeplay::planning
