#include "freeplay/planning/reach.hpp"

#include <cmath>

namespace freeplay::planning {

double reach_disc_radius(double reach, double shoulder_height) {
  const double squared = reach * reach - shoulder_height * shoulder_height;
  return squared > 0.0 ? std::sqrt(squared) : 0.0;
}

bool in_reach_disc(const Vec2& point, const Vec2& shoulder_xy, double reach, double shoulder_height) {
  return (point - shoulder_xy).norm() < reach_disc_radius(reach, shoulder_height);
}

}  // namespace freeplay::planning
