#pragma once
// The shared set of planning cases of the planner benchmarks: random layouts with 0, 5 and 10 items.

#include <string>
#include <vector>

#include "freeplay/core/rng.hpp"
#include "freeplay/planning/layout.hpp"
#include "freeplay/planning/plan.hpp"

namespace freeplay::planning::bench {

/// Budgets per planner: the anytime planners get a fixed iteration count (RRT*) or a short time (BIT*).
inline void apply_budget(const std::string& planner, PlanRequest& request) {
  request.time_budget_s = planner == "bitstar" ? 0.05 : 1.0;
  request.iteration_budget = planner == "rrtstar" ? 1000 : 0;
}

/// `count` requests on layouts of `n_items` items: a random item moves to a random free point (>= 1 cm from
/// every footprint); with no items the start is a random point.
inline std::vector<PlanRequest> make_cases(int n_items, int count, std::uint64_t seed) {
  const auto shapes = approximate_item_shapes();
  Rng rng(seed);
  std::vector<PlanRequest> cases;
  while (static_cast<int>(cases.size()) < count) {
    const Layout layout = random_layout(shapes, n_items, rng);
    PlanRequest request;
    request.obstacles = layout.obstacles();
    if (n_items > 0) {
      const auto& moved = layout.items[static_cast<std::size_t>(rng.uniform_int(0, n_items - 1))];
      request.item = moved.name;
      request.start = moved.pose.position();
      request.moved_footprint = moved.footprint;
    } else {
      request.item = "ball";
      request.start = {rng.uniform(0.02, 0.508), rng.uniform(-0.315, -0.02)};
    }
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const Vec2 goal{rng.uniform(0.02, 0.508), rng.uniform(-0.315, -0.02)};
      bool clear = (goal - request.start).norm() > 0.05;
      for (const auto& obstacle : request.obstacles) {
        if (obstacle.name != request.item && signed_distance(obstacle.footprint, goal) < 0.01) clear = false;
      }
      if (clear) {
        request.goal = goal;
        cases.push_back(request);
        break;
      }
    }
  }
  return cases;
}

}  // namespace freeplay::planning::bench
