#pragma once
// The sandtray as the move executor sees it: TF item centres, `/footprints` polygons moved by TF (every item,
// the stash included, as the real map_and_plan), and the children's fingers on items.

#include <memory>

#include "freeplay/planning/move_executor.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::scenario {
struct Scenario;
}

namespace freeplay::runner {

/// Callbacks reading `tray` (which must outlive the returned world) for `planning::MoveExecutor`.
planning::MoveWorld sandtray_move_world(const sim::Sandtray& tray);

/// The move executor of a scenario (its planner, budget, finger speed and goal checks) for a robot whose right
/// shoulder projects to `shoulder_xy` and whose reach disc on the table has radius `disc_radius` (m).
std::unique_ptr<planning::MoveExecutor> make_move_executor(const scenario::Scenario& scenario, const Vec2& shoulder_xy,
                                                           double disc_radius);

}  // namespace freeplay::runner
