#pragma once
// Pan/tilt that points an eye, offset from the pan/tilt pivot, at a target (shared by the NAO and the avatars).

#include <Eigen/Core>
#include <cmath>

namespace freeplay::stage {

/// Head angles: yaw about z, then pitch about the turned y axis (+ = look down).
struct PanTilt {
  double yaw = 0;    ///< rad
  double pitch = 0;  ///< rad
};

/// Angles that put `target` (in the pivot frame, x forward, z up) on the eye's forward ray; the eye sits at
/// `eye_offset` (x forward, z up) in the head frame and looks along the head's x axis.
inline PanTilt pan_tilt_towards(const Eigen::Vector3d& target, const Eigen::Vector3d& eye_offset) {
  PanTilt angles;
  angles.yaw = std::atan2(target.y(), target.x());
  const double forward = std::hypot(target.x(), target.y());
  // Fixed-point iteration on the eye's height offset, which moves as the head pitches.
  for (int i = 0; i < 4; ++i) {
    const double c = std::cos(angles.pitch);
    const double s = std::sin(angles.pitch);
    const double eye_x = c * eye_offset.x() + s * eye_offset.z();
    const double eye_z = -s * eye_offset.x() + c * eye_offset.z();
    // The ray from the eye along the pitched x axis passes through the target when the eye's perpendicular
    // offset from the pivot-target line is accounted for.
    const double along = forward - eye_x;
    const double down = eye_z - target.z();
    angles.pitch = std::atan2(down, along);
  }
  return angles;
}

}  // namespace freeplay::stage
