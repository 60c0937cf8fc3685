#pragma once
// Small map builders shared by the planning tests.

#include <string>

#include "freeplay/planning/plan.hpp"

namespace freeplay::planning::testing {

/// Axis-aligned rectangle obstacle [x0, x1] × [y0, y1] (sandtray frame).
inline Obstacle box(std::string name, double x0, double x1, double y0, double y1) {
  return {std::move(name), {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
}

}  // namespace freeplay::planning::testing
