#pragma once
// The robot's body as the episode loop needs it: where its arm reaches, and where its fingertip and gaze go
// when it follows the virtual finger (`nao_behaviours`). Implemented by the MuJoCo Nao of the stage library.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>

#include "freeplay/core/geometry.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/stage/stage_mode.hpp"

namespace freeplay::runner {

/// The `arm_reach` frame: shoulder projected on the table and the reachable disc's radius.
struct ReachDisc {
  Vec2 centre = Vec2::Zero();  ///< RShoulder projected on the screen plane (sandtray frame)
  double radius = 0.0;         ///< √(reach² − h²)
};

/// The robot's body during one episode (one instance per episode and thread).
class RobotBody {
 public:
  virtual ~RobotBody() = default;
  /// The arm-reach disc at table level.
  virtual ReachDisc reach() const = 0;
  /// Points the right arm at the finger pose `p` and looks at it (one `/poses` message, as nao_behaviours);
  /// returns the fingertip's projection on the screen afterwards.
  virtual Vec2 follow_finger(const Vec2& p) = 0;
  /// Turns the head towards a 3-D point in `sandtray`.
  virtual void look_at(const Eigen::Vector3d& point) = 0;
  /// Points at a screen point without a finger stream (PointAt).
  virtual void point_at(const Vec2& p) = 0;
  /// Returns the arm to its rest posture (after 30 s without poses, as nao_behaviours).
  virtual void rest() = 0;
  /// Where a seated child's face is (for LookAt child and mutual gaze), by seat name.
  virtual Eigen::Vector3d child_face(const std::string& seat) const = 0;
  /// Fills the joint names, positions, velocities and efforts of `snapshot` (sensor_msgs/JointState).
  virtual void joint_state(RobotSnapshot& snapshot) const { (void)snapshot; }
};

/// Builds a robot body for the robot mode of a scenario and its arm reach (m).
using RobotBodyFactory = std::function<std::unique_ptr<RobotBody>(stage::StageMode mode, double arm_reach)>;

}  // namespace freeplay::runner
