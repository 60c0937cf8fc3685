#pragma once
// An optional replacement for the robot's policy and move executor in a child-robot episode: something outside the
// episode (a live ROS graph: `freeplay serve --robot external`) moves the robot's virtual finger, and the episode
// applies each pose as the game applies `/poses` (the Nao follows it, as nao_behaviours).

#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/runner/robot_body.hpp"

namespace freeplay::sim {
class Sandtray;
}

namespace freeplay::runner {

/// Supplies the robot's finger poses of an episode instead of its policy and move executor.
class RobotActionSource {
 public:
  virtual ~RobotActionSource() = default;
  /// The robot-finger poses (sandtray frame, in order) to apply during the free-play tick that starts at `t` (s since
  /// free play started); `tray` is the game as it is now and `reach` the robot's arm-reach disc (read only).
  virtual std::vector<Vec2> finger_poses(double t, const sim::Sandtray& tray, const ReachDisc& reach) = 0;
};

}  // namespace freeplay::runner
