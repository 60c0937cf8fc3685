#pragma once
// A sandtray with one item for the robot side's and the move driver's tests.

#include <optional>
#include <string>
#include <vector>

#include "freeplay/planning/move_executor.hpp"

namespace freeplay::runner::test {

/// The executor's view of a table with one item, "ball" (a 4 cm square centred at `ball`), read through the
/// references at every call; `held`: a child's finger is on it.
inline planning::MoveWorld one_ball_world(const Vec2& ball, const bool& held) {
  planning::MoveWorld w;
  w.item_centre = [&ball](const std::string& item) -> std::optional<Vec2> {
    if (item != "ball") return std::nullopt;
    return ball;
  };
  w.footprints = [&ball] {
    const Polygon2 square{ball + Vec2(-0.02, -0.02), ball + Vec2(0.02, -0.02), ball + Vec2(0.02, 0.02),
                          ball + Vec2(-0.02, 0.02)};
    return std::vector<planning::Obstacle>{{"ball", square}};
  };
  w.held_by_child = [&held](const std::string&) { return held; };
  return w;
}

}  // namespace freeplay::runner::test
