// OMPL planners on the shared occupancy grid: validity, determinism from the seed, re-timing.

#include <gtest/gtest.h>

#include "freeplay/planning/ompl_planner.hpp"
#include "freeplay/planning/plan.hpp"
#include "test_helpers.hpp"

namespace freeplay::planning {
namespace {

using testing::box;

PlanRequest request_between(Vec2 start, Vec2 goal, std::vector<Obstacle> obstacles) {
  PlanRequest request;
  request.item = "mover";
  request.start = start;
  request.goal = goal;
  request.obstacles = std::move(obstacles);
  request.time_budget_s = 5.0;
  return request;
}

std::vector<Obstacle> wall_with_gap() {
  return {box("upper", 0.2525, 0.2675, -0.1525, 0.1), box("lower", 0.2525, 0.2675, -0.5, -0.1875)};
}

std::vector<Obstacle> clutter() {
  return {box("a", 0.10, 0.14, -0.10, -0.05), box("b", 0.20, 0.26, -0.25, -0.12), box("c", 0.33, 0.37, -0.09, -0.02),
          box("d", 0.40, 0.45, -0.30, -0.18)};
}

std::vector<Vec2> positions(const PlanResult& result) {
  std::vector<Vec2> out;
  for (const auto& pose : result.path) out.push_back(pose.position);
  return out;
}

class EveryOmplPlanner : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryOmplPlanner, CrossesAWallThroughItsGapWithAValidRetimedPath) {
  const auto planner = make_planner(GetParam());
  Rng rng(11);
  const auto obstacles = wall_with_gap();
  PlanRequest request = request_between({0.1, -0.05}, {0.4, -0.05}, obstacles);
  // BIT* cannot be seeded (see docs): give it a short wall-clock budget instead of an iteration budget.
  const bool bitstar = std::string(GetParam()) == "bitstar";
  request.time_budget_s = bitstar ? 0.3 : 2.0;
  request.iteration_budget = bitstar ? 0 : 300;
  const PlanResult result = planner->plan(request, rng);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.path.front().position, request.start);
  EXPECT_EQ(result.path.back().position, request.goal);
  bool crossed = false;
  for (std::size_t i = 0; i < result.path.size(); ++i) {
    const auto& pose = result.path[i];
    EXPECT_NEAR(pose.t, 0.1 * static_cast<double>(i), 1e-9);
    if (i > 0) {
      EXPECT_LE((pose.position - result.path[i - 1].position).norm(), 0.005 + 1e-12);
    }
    for (const auto& obstacle : obstacles) {
      EXPECT_GT(signed_distance(obstacle.footprint, pose.position), -0.005) << "deep inside " << obstacle.name;
    }
    // Rim cells with occupancy < 50 are free, so near-optimal paths may cut a wall corner by up to one cell.
    if (pose.position.x() > 0.2525 && pose.position.x() < 0.2675) {
      crossed = true;
      EXPECT_GT(pose.position.y(), -0.1875 - 0.005);
      EXPECT_LT(pose.position.y(), -0.1525 + 0.005);
    }
  }
  EXPECT_TRUE(crossed);
  EXPECT_GT(result.metrics.expanded_nodes, 0U);
  EXPECT_NEAR(result.metrics.path_length_m, (result.path.size() - 1) * 0.005, 0.005 * 0.5 * result.path.size());
}

TEST_P(EveryOmplPlanner, EnclosedGoalHasNoPathAndGoalInAnItemIsRejected) {
  const auto planner = make_planner(GetParam());
  Rng rng(11);
  const std::vector<Obstacle> ring = {box("n", 0.25, 0.35, -0.14, -0.12), box("s", 0.25, 0.35, -0.22, -0.20),
                                      box("w", 0.25, 0.27, -0.22, -0.12), box("e", 0.33, 0.35, -0.22, -0.12)};
  EXPECT_EQ(planner->plan(request_between({0.1, -0.05}, {0.3, -0.17}, ring), rng).reason, FailureReason::NoPath);
  EXPECT_EQ(planner->plan(request_between({0.1, -0.05}, {0.3, -0.13}, ring), rng).reason,
            FailureReason::GoalInsideObstacle);
  EXPECT_EQ(planner->plan(request_between({0.1, -0.05}, {0.3, -0.4}, ring), rng).reason,
            FailureReason::GoalOffScreen);
}

INSTANTIATE_TEST_SUITE_P(Planners, EveryOmplPlanner, ::testing::Values("rrtconnect", "prmstar", "rrtstar", "bitstar"));

class SeededOmplPlanner : public ::testing::TestWithParam<const char*> {};

TEST_P(SeededOmplPlanner, SameSeedGivesTheSamePathAndOtherSeedsUsuallyDiffer) {
  const auto planner = make_planner(GetParam());
  PlanRequest request = request_between({0.05, -0.3}, {0.5, -0.03}, clutter());
  request.iteration_budget = 400;  // RRT*: iteration-limited, so the clock plays no part
  const auto run = [&](std::uint64_t seed) {
    Rng rng(seed);
    const PlanResult result = planner->plan(request, rng);
    EXPECT_TRUE(result.ok) << result.message;
    return positions(result);
  };
  const auto first = run(42);
  EXPECT_EQ(first, run(42));
  EXPECT_EQ(first, run(42));
  int different = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) different += run(seed) != first ? 1 : 0;
  EXPECT_GE(different, 3);
}

INSTANTIATE_TEST_SUITE_P(Planners, SeededOmplPlanner, ::testing::Values("rrtconnect", "prmstar", "rrtstar"));

TEST(OmplPlanner, StartOnAnotherItemsRimEscapesDownhill) {
  const auto planner = make_planner("rrtconnect");
  Rng rng(3);
  // The start lies 2 mm inside the rock's right edge (blurred occupancy >= 50), the goal is free.
  const std::vector<Obstacle> rock = {box("rock", 0.2, 0.3, -0.2, -0.1)};
  const PlanResult result = planner->plan(request_between({0.298, -0.15}, {0.45, -0.15}, rock), rng);
  ASSERT_TRUE(result.ok) << result.message;
}

TEST(OmplPlanner, FingerSpeedSetsThePoseSpacing) {
  PlannerOptions options;
  options.finger_speed_mps = 0.1;
  const auto planner = make_planner("rrtconnect", options);
  Rng rng(3);
  const PlanResult result = planner->plan(request_between({0.05, -0.05}, {0.5, -0.3}, {}), rng);
  ASSERT_TRUE(result.ok);
  ASSERT_EQ(result.path.size(), 1 + static_cast<std::size_t>(std::ceil((Vec2(0.45, -0.25)).norm() / 0.01)));
  for (std::size_t i = 1; i < result.path.size(); ++i) {
    EXPECT_LE((result.path[i].position - result.path[i - 1].position).norm(), 0.01 + 1e-12);
  }
}

TEST(RetimePath, SplitsSegmentsIntoEqualPiecesNoLongerThanOneStep) {
  const auto poses = retime_path({{0.0, 0.0}, {0.012, 0.0}, {0.012, 0.0}, {0.012, -0.005}}, 0.05, 0.1);
  ASSERT_EQ(poses.size(), 5U);  // 3 pieces of 4 mm, then one of 5 mm; the repeated point is skipped
  EXPECT_NEAR(poses[1].position.x(), 0.004, 1e-12);
  EXPECT_NEAR(poses[3].position.x(), 0.012, 1e-12);
  EXPECT_NEAR(poses[4].position.y(), -0.005, 1e-12);
  EXPECT_DOUBLE_EQ(poses[4].t, 0.4);
  EXPECT_TRUE(retime_path({}, 0.05, 0.1).empty());
}

}  // namespace
}  // namespace freeplay::planning
