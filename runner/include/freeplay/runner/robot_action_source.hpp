#pragma once
// The robot's finger poses from outside a child-robot episode: something outside the episode (a live ROS graph's
// `/poses` under `freeplay serve --robot external`) moves the robot's virtual finger, and the episode applies each
// pose as the game applies `/poses` (the Nao follows it, as nao_behaviours), and turns the Nao's head and arm to the
// gaze and pointing targets it sends. Alone it replaces the robot side; beside an action source in front of the robot
// side (EpisodeInputs::decisions) both act, the poses first.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/runner/robot_body.hpp"

namespace freeplay::sim {
class Sandtray;
}

namespace freeplay::runner {

/// One utterance of the robot: what it says and to whom ("", "purple", "yellow").
struct RobotUtterance {
  std::string text;  ///< the words (the Nao's TTS input)
  std::string to;    ///< addressee; empty: everyone
};

/// What an external robot does during one free-play tick.
struct RobotCommands {
  std::vector<Vec2> finger;                   ///< robot-finger poses (`/poses`, sandtray frame), in order
  std::optional<Eigen::Vector3d> look_at;     ///< a gaze target (sandtray frame, m)
  std::optional<Vec2> point_at;               ///< a pointing target on the screen (sandtray frame, m)
  std::vector<RobotUtterance> say;            ///< utterances started this tick (as a policy's `say`: heard, logged)
};

/// Supplies the robot's finger poses (and, alone, its gaze, pointing and speech) from outside the episode.
class RobotActionSource {
 public:
  virtual ~RobotActionSource() = default;
  /// What the robot does during the free-play tick that starts at `t` (s since free play started); `tray` is the
  /// game as it is now and `reach` the robot's arm-reach disc (read only).
  virtual RobotCommands commands(double t, const sim::Sandtray& tray, const ReachDisc& reach) = 0;
};

}  // namespace freeplay::runner
