// The planner registry and request checks.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/plan.hpp"
#include "test_helpers.hpp"

namespace freeplay::planning {
namespace {

PlanRequest simple_request() {
  PlanRequest request;
  request.item = "zebra";
  request.start = {0.1, -0.1};
  request.goal = {0.2, -0.2};
  request.obstacles = {testing::box("zebra", 0.09, 0.11, -0.11, -0.09)};
  request.time_budget_s = 0.05;  // the anytime planners use all of it
  return request;
}

TEST(Registry, KnowsEveryPlannerByName) {
  const std::vector<std::string> expected = {"astar", "bitstar", "prmstar", "rrtconnect", "rrtstar"};
  EXPECT_EQ(planner_names(), expected);
  for (const auto& name : planner_names()) EXPECT_EQ(make_planner(name)->name(), name);
}

TEST(Registry, UnknownNameListsTheAllowedOnes) {
  try {
    make_planner("dijkstra");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "planner");
    EXPECT_EQ(error.allowed(), "astar, bitstar, prmstar, rrtconnect, rrtstar");
    EXPECT_NE(std::string(error.what()).find("dijkstra"), std::string::npos);
  }
}

TEST(Requests, NonFiniteGoalsAndStartsAreInputErrors) {
  for (const auto& name : planner_names()) {
    const auto planner = make_planner(name);
    Rng rng(1);
    PlanRequest request = simple_request();
    request.goal.x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(planner->plan(request, rng), InputError) << name;
    request = simple_request();
    request.goal.y() = std::numeric_limits<double>::infinity();
    EXPECT_THROW(planner->plan(request, rng), InputError) << name;
    request = simple_request();
    request.start.x() = -std::numeric_limits<double>::infinity();
    EXPECT_THROW(planner->plan(request, rng), InputError) << name;
    request = simple_request();
    request.time_budget_s = 0.0;
    EXPECT_THROW(planner->plan(request, rng), InputError) << name;
    request = simple_request();
    request.obstacles.push_back({"flat", {{0.3, -0.1}, {0.31, -0.1}}});
    EXPECT_THROW(planner->plan(request, rng), InputError) << name;
  }
}

TEST(Requests, PlanOrReportTurnsInputErrorsIntoInvalidRequest) {
  const auto planner = make_planner("astar");
  Rng rng(1);
  PlanRequest request = simple_request();
  request.goal.x() = std::numeric_limits<double>::quiet_NaN();
  const PlanResult result = plan_or_report(*planner, request, rng);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.reason, FailureReason::InvalidRequest);
  EXPECT_NE(result.message.find("goal"), std::string::npos);
  EXPECT_EQ(failure_reason_name(result.reason), "invalid_request");
}

TEST(Requests, EveryPlannerDrawsExactlyOneValueFromTheStream) {
  for (const auto& name : planner_names()) {
    Rng rng(9);
    Rng reference(9);
    static_cast<void>(reference());
    const PlanResult result = plan_motion(name, simple_request(), rng);
    EXPECT_TRUE(result.ok) << name << ": " << result.message;
    EXPECT_EQ(rng(), reference()) << name;
  }
}

TEST(Requests, MovedItemIsIgnoredAndItsFootprintGivesTheClearance) {
  PlanRequest request = simple_request();
  request.obstacles.push_back(testing::box("rock", 0.25, 0.30, -0.30, -0.25));
  request.moved_footprint = request.obstacles.front().footprint;
  Rng rng(2);
  const PlanResult result = plan_motion("astar", request, rng);
  ASSERT_TRUE(result.ok);
  // The zebra (1 cm half-side) ends near (0.2, −0.2); the rock's corner is at (0.25, −0.25).
  EXPECT_GT(result.metrics.min_clearance_m, 0.0);
  EXPECT_LT(result.metrics.min_clearance_m, (Vec2(0.25, -0.25) - Vec2(0.21, -0.21)).norm() + 0.006);
}

}  // namespace
}  // namespace freeplay::planning
