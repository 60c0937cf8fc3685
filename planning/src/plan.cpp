#include "freeplay/planning/plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/astar.hpp"
#include "freeplay/planning/layout.hpp"
#include "freeplay/planning/ompl_planner.hpp"
#include "path_metrics.hpp"

namespace freeplay::planning {

namespace {

bool on_screen(const Vec2& p) {
  return p.x() >= 0.0 && p.x() <= OccupancyGrid::kWidthM && p.y() <= 0.0 && p.y() >= -OccupancyGrid::kHeightM;
}

// Signed distance between a moved body and an obstacle: positive gap when apart, negative depth when overlapping.
double body_clearance(const Polygon2& body, const Polygon2& obstacle) {
  if (!polygons_intersect(body, obstacle)) return polygon_distance(body, obstacle);
  double depth = 0.0;
  for (const auto& v : body) depth = std::min(depth, signed_distance(obstacle, v));
  for (const auto& w : obstacle) depth = std::min(depth, signed_distance(body, w));
  return depth;
}

}  // namespace

std::string_view failure_reason_name(FailureReason reason) {
  switch (reason) {
    case FailureReason::None: return "none";
    case FailureReason::GoalOffScreen: return "goal_off_screen";
    case FailureReason::GoalInsideObstacle: return "goal_inside_obstacle";
    case FailureReason::NoPath: return "no_path";
    case FailureReason::TimeBudgetExceeded: return "time_budget_exceeded";
    case FailureReason::InvalidRequest: return "invalid_request";
  }
  return "unknown";
}

std::vector<std::string> planner_names() {
  std::vector<std::string> names(kPlannerNames.begin(), kPlannerNames.end());
  std::sort(names.begin(), names.end());
  return names;
}

std::string planner_names_joined() {
  std::string out;
  for (const auto& name : planner_names()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

std::unique_ptr<MotionPlanner> make_planner(std::string_view name, const PlannerOptions& options) {
  if (name == "astar") return std::make_unique<AStarPlanner>(options);
  if (name == "rrtconnect") return std::make_unique<OmplPlanner>(OmplAlgorithm::RRTConnect, options);
  if (name == "prmstar") return std::make_unique<OmplPlanner>(OmplAlgorithm::PRMstar, options);
  if (name == "rrtstar") return std::make_unique<OmplPlanner>(OmplAlgorithm::RRTstar, options);
  if (name == "bitstar") return std::make_unique<OmplPlanner>(OmplAlgorithm::BITstar, options);
  throw InputError(fmt::format("unknown planner '{}'", name), "planner", planner_names_joined());
}

PlannerOptions planner_options(const PlannerSettings& settings) {
  PlannerOptions options;
  // The real A* plans to any point; 101 exceeds every occupancy, so no goal is refused for lying on items.
  if (!settings.reject_blocked_goals) options.goal_blocked_occupancy = 101;
  return options;
}

std::unique_ptr<MotionPlanner> make_planner(const PlannerSettings& settings) {
  return make_planner(settings.name, planner_options(settings));
}

void validate_request(const PlanRequest& request) {
  const auto finite_vertex = [](const Vec2& p) { return p.allFinite(); };
  if (!request.start.allFinite()) {
    throw InputError(fmt::format("start ({}, {}) is not finite", request.start.x(), request.start.y()), "start",
                     "finite x, y in metres (sandtray frame)");
  }
  if (!request.goal.allFinite()) {
    throw InputError(fmt::format("goal ({}, {}) is not finite", request.goal.x(), request.goal.y()), "goal",
                     "finite x, y in metres (sandtray frame)");
  }
  if (!(request.time_budget_s > 0.0) || !std::isfinite(request.time_budget_s)) {
    throw InputError(fmt::format("time budget {} s is not a positive finite number", request.time_budget_s),
                     "time_budget_s", "> 0");
  }
  for (std::size_t i = 0; i < request.obstacles.size(); ++i) {
    const auto& footprint = request.obstacles[i].footprint;
    const bool ok = footprint.size() >= 3 && std::all_of(footprint.begin(), footprint.end(), finite_vertex);
    if (!ok) {
      throw InputError(fmt::format("footprint of '{}' needs at least 3 finite vertices", request.obstacles[i].name),
                       fmt::format("obstacles[{}].footprint", i), "polygon of >= 3 finite vertices");
    }
  }
  if (request.moved_footprint) {
    const auto& footprint = *request.moved_footprint;
    if (footprint.size() < 3 || !std::all_of(footprint.begin(), footprint.end(), finite_vertex)) {
      throw InputError("moved footprint needs at least 3 finite vertices", "moved_footprint",
                       "polygon of >= 3 finite vertices");
    }
  }
}

PlanResult plan_or_report(const MotionPlanner& planner, const PlanRequest& request, Rng& rng) {
  try {
    return planner.plan(request, rng);
  } catch (const InputError& error) {
    return detail::failure(FailureReason::InvalidRequest, error.what());
  }
}

PlanResult plan_motion(std::string_view planner_name, const PlanRequest& request, Rng& rng,
                       const PlannerOptions& options) {
  return make_planner(planner_name, options)->plan(request, rng);
}

namespace detail {

PlanResult failure(FailureReason reason, std::string message) {
  PlanResult result;
  result.ok = false;
  result.reason = reason;
  result.message = std::move(message);
  return result;
}

std::optional<PlanResult> check_goal(const PlanRequest& request, const OccupancyGrid& grid,
                                     const PlannerOptions& options) {
  if (!on_screen(request.goal)) {
    return failure(FailureReason::GoalOffScreen,
                   fmt::format("goal ({:.4f}, {:.4f}) lies outside the screen [0, 0.6] x [-0.335, 0]",
                               request.goal.x(), request.goal.y()));
  }
  const Cell goal_cell = OccupancyGrid::clamp(OccupancyGrid::cell_of(request.goal));
  const int occupancy = grid.occupancy(goal_cell);
  if (occupancy >= options.goal_blocked_occupancy) {
    return failure(FailureReason::GoalInsideObstacle,
                   fmt::format("goal ({:.4f}, {:.4f}) lies inside another item (cell occupancy {} >= {})",
                               request.goal.x(), request.goal.y(), occupancy, options.goal_blocked_occupancy));
  }
  return std::nullopt;
}

void measure_path(const PlanRequest& request, PlanResult& result) {
  double length = 0.0;
  for (std::size_t i = 1; i < result.path.size(); ++i) {
    length += (result.path[i].position - result.path[i - 1].position).norm();
  }
  result.metrics.path_length_m = length;

  // A polygon lies inside its bounding box, so two disjoint boxes bound the clearance from below by their gap: a
  // pair whose boxes are farther apart than the current minimum cannot lower it and is skipped (same result, less
  // work). Overlapping boxes say nothing (the clearance may be a negative depth) and are always measured.
  struct Box {
    Vec2 lo, hi;
  };
  const auto gap = [](const Box& a, const Box& b) {
    const double dx = std::max({0.0, a.lo.x() - b.hi.x(), b.lo.x() - a.hi.x()});
    const double dy = std::max({0.0, a.lo.y() - b.hi.y(), b.lo.y() - a.hi.y()});
    return std::hypot(dx, dy);
  };
  std::vector<Box> boxes;
  boxes.reserve(request.obstacles.size());
  for (const auto& obstacle : request.obstacles) {
    const auto [lo, hi] = bounds(obstacle.footprint);
    boxes.push_back({lo, hi});
  }
  Box moved{Vec2::Zero(), Vec2::Zero()};
  if (request.moved_footprint) {
    const auto [lo, hi] = bounds(*request.moved_footprint);
    moved = {lo, hi};
  }
  double clearance = std::numeric_limits<double>::infinity();
  Polygon2 body;
  for (const auto& pose : result.path) {
    const Vec2 shift = pose.position - request.start;
    const Box here = request.moved_footprint ? Box{moved.lo + shift, moved.hi + shift} : Box{pose.position, pose.position};
    for (std::size_t k = 0; k < request.obstacles.size(); ++k) {
      const auto& obstacle = request.obstacles[k];
      if (obstacle.name == request.item) continue;
      const double box_gap = gap(here, boxes[k]);
      if (box_gap > 0.0 && box_gap > clearance + 1e-9) continue;  // the margin absorbs rounding
      if (request.moved_footprint) {
        body = *request.moved_footprint;
        for (auto& v : body) v += shift;
        clearance = std::min(clearance, body_clearance(body, obstacle.footprint));
      } else {
        clearance = std::min(clearance, signed_distance(obstacle.footprint, pose.position));
      }
    }
  }
  result.metrics.min_clearance_m = clearance;
}

}  // namespace detail

}  // namespace freeplay::planning
