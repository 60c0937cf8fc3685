#pragma once
// Internal helpers shared by the planners: request checks, metrics of a finished path.

#include <string>
#include <vector>

#include "freeplay/planning/occupancy_grid.hpp"
#include "freeplay/planning/plan.hpp"

namespace freeplay::planning::detail {

/// Fills `result.metrics.path_length_m` and `min_clearance_m` from `result.path`.
void measure_path(const PlanRequest& request, PlanResult& result);
/// A failed result with the given reason and message.
PlanResult failure(FailureReason reason, std::string message);
/// Checks the goal against the screen and the grid; returns a failure or nullopt when the goal is acceptable.
std::optional<PlanResult> check_goal(const PlanRequest& request, const OccupancyGrid& grid,
                                     const PlannerOptions& options);

}  // namespace freeplay::planning::detail
