#pragma once
// The real system's grid A* (`map_and_plan`), usable directly on a grid for tests and tools.

#include <vector>

#include "freeplay/planning/occupancy_grid.hpp"
#include "freeplay/planning/plan.hpp"

namespace freeplay::planning {

/// Outcome of a grid search.
struct GridSearchResult {
  bool found = false;              ///< a path was found within the time budget
  bool timed_out = false;          ///< the search stopped on the time budget
  std::vector<Cell> cells;         ///< start cell … goal cell
  double cost = 0.0;               ///< sum of the step costs of every entered cell
  std::uint64_t expanded = 0;      ///< nodes taken from the open list
};

/// Expansions the A* budget grants per second of `time_budget_s` (a deterministic stand-in for wall time, about
/// what one core of the project's machine expands per second), so a plan never depends on the machine's load.
inline constexpr double kAStarExpansionsPerBudgetSecond = 1.0e7;

/// 8-connected A* with step cost = cost of the entered cell; may leave the map by `outside_margin_cells`. Stops
/// (timed_out) after time_budget_s × kAStarExpansionsPerBudgetSecond expansions; it reads no clock.
GridSearchResult astar_search(const OccupancyGrid& grid, const Cell& start, const Cell& goal,
                              AStarHeuristic heuristic, int outside_margin_cells, double time_budget_s);

/// The `astar` planner of the registry: faithful to `map_and_plan` (see docs/planning.md).
class AStarPlanner final : public MotionPlanner {
 public:
  /// Keeps a copy of the options.
  explicit AStarPlanner(PlannerOptions options = {}) : options_(options) {}
  /// "astar".
  std::string_view name() const override { return "astar"; }
  /// Plans on the 5 mm grid; path poses at cell points stamped i × pose period.
  PlanResult plan(const PlanRequest& request, Rng& rng) const override;

 private:
  PlannerOptions options_;
};

}  // namespace freeplay::planning
