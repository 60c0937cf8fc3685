#pragma once
// The sandtray as the move executor sees it: TF item centres, `/footprints` polygons moved by TF (every item,
// the stash included, as the real map_and_plan), and the children's fingers on items.

#include "freeplay/planning/move_executor.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::runner {

/// Callbacks reading `tray` (which must outlive the returned world) for `planning::MoveExecutor`.
planning::MoveWorld sandtray_move_world(const sim::Sandtray& tray);

}  // namespace freeplay::runner
