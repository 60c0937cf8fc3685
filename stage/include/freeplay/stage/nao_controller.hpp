#pragma once
// NAO control on the stage: postures, gaze with NAOqi's head limits, pointing by inverse kinematics.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "freeplay/stage/nao_description.hpp"
#include "freeplay/stage/stage.hpp"

namespace freeplay::stage {

/// Outcome of a gaze command.
struct GazeResult {
  double yaw = 0;        ///< commanded head yaw (rad)
  double pitch = 0;      ///< commanded head pitch (rad, + = down)
  bool clamped = false;  ///< true when the limits kept the head from facing the target exactly
};

/// Outcome of a pointing command.
struct PointingResult {
  bool reachable = false;                        ///< fingertip within 5 mm (on the screen plane) of the target
  double error_m = 0;                            ///< distance on the screen plane between fingertip and target
  double height_m = 0;                           ///< fingertip height above the screen
  Eigen::Vector3d fingertip = Eigen::Vector3d::Zero();  ///< fingertip position the joints produce (sandtray)
};

/// A target on the screen at a given time (for synchronised drags).
struct TimedScreenPoint {
  double time = 0;                                 ///< seconds
  Eigen::Vector2d point = Eigen::Vector2d::Zero(); ///< sandtray x, y (m)
};

/// The `arm_reach` disc of the real system: RShoulder projected on the table, radius √(reach² − h²).
struct ArmReachDisc {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< sandtray x, y (m)
  double radius = 0;                                 ///< 0 when the shoulder is higher above the table than reach
  bool too_high = false;                             ///< the real node's "Too high!" warning
};

/// Drives the stage's NAO: kinematic mode writes joint angles, dynamic mode sets position-actuator targets.
class NaoController {
 public:
  /// Fingertip height above the screen when pointing (m): the real robot touches the screen only virtually.
  static constexpr double kHoverHeight = 0.02;
  /// Largest on-screen error for which a target counts as reached (m).
  static constexpr double kReachTolerance = 0.005;
  /// Highest fingertip above the screen at which a target counts as reached (m).
  static constexpr double kMaxReachHeight = 0.1;

  /// Controls the NAO of `stage`; throws InputError when the scene has no NAO.
  explicit NaoController(Stage& stage);
  ~NaoController();
  NaoController(const NaoController&) = delete;
  NaoController& operator=(const NaoController&) = delete;

  /// Commands a predefined posture and places the robot with its soles flat on the floor at its station.
  void go_to_posture(NaoPosture posture);
  /// Commands joint angles (clamped to the joint ranges; RHipYawPitch follows LHipYawPitch).
  void set_joint_targets(const NaoJointVector& targets);
  /// The last commanded joint angles.
  const NaoJointVector& joint_targets() const { return targets_; }
  /// The joint angles the stage holds now.
  NaoJointVector joint_positions() const;

  /// Turns the head towards `point` (sandtray), respecting the yaw-dependent head pitch limits.
  GazeResult look_at(const Eigen::Vector3d& point);
  /// Puts the right fingertip kHoverHeight above `screen_point` by damped-least-squares IK on the right arm.
  PointingResult point_at(const Eigen::Vector2d& screen_point);
  /// Sets a timed path of screen points (times strictly increasing); throws InputError otherwise.
  void follow_path(std::vector<TimedScreenPoint> path);
  /// Points at the path's point for `time` (linear interpolation, held at the ends).
  PointingResult update(double time);
  /// The path's target at `time`.
  Eigen::Vector2d path_point(double time) const;

  /// Opens (1) or closes (0) the hands; values are clamped to [0, 1].
  void set_hands(double left_opening, double right_opening);

  /// The real system's arm reach disc for the current pose.
  ArmReachDisc arm_reach() const;
  /// Dynamic mode: refreshes gravity feed-forward of the position targets (call once per control tick).
  void apply();

 private:
  void write_targets();
  void place_base(const NaoJointVector& posture);
  // Where the right arm's chain hangs from: its base body's pose (sandtray frame).
  struct ArmBase {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  };
  ArmBase load_arm();
  PointingResult solve_pointing(const ArmBase& base, const Eigen::Vector3d& target, const NaoJointVector& seed,
                                bool retry, NaoJointVector* out);

  Stage& stage_;
  const NaoIndex& nao_;
  NaoJointVector targets_{};
  struct Scratch;                              // a MuJoCo state for trial poses and gravity (nao_controller.cpp)
  std::unique_ptr<Scratch> scratch_;
  std::shared_ptr<class ArmChain> arm_chain_;  // the right arm's kinematic chain (pointing IK)
  std::vector<TimedScreenPoint> path_;
};

}  // namespace freeplay::stage
