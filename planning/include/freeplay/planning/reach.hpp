#pragma once
// The robot's arm reach as the real `sandtray_localisation` publishes it (`arm_reach` frame).

#include "freeplay/core/geometry.hpp"

namespace freeplay::planning {

/// Radius of the reachable disc at table level, √(reach² − h²); 0 when the shoulder is higher than the reach.
double reach_disc_radius(double reach, double shoulder_height);
/// True when `point` lies strictly inside the disc of radius √(reach² − h²) around `shoulder_xy` (play policy rule).
bool in_reach_disc(const Vec2& point, const Vec2& shoulder_xy, double reach, double shoulder_height);

}  // namespace freeplay::planning
