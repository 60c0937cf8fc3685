#pragma once
// What the real `sandtray_localisation` node does, without ROS: on `robot_localising` it looks for the marker field
// in the robot's camera for at most 5 s; on success it computes odom→sandtray once (odom→camera at that frame ×
// camera→field), holds it and says "I know where I am now!"; on a timeout it says "I am lost!" and keeps what it
// had. From the held transform it derives the `arm_reach` frame.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/localisation/field_pose.hpp"
#include "freeplay/localisation/marker_field.hpp"

namespace freeplay::localisation {

/// The node's parameters (names and defaults of `sandtray_localisation`; play.launch sets the arm-reach ones).
struct LocaliserSettings {
  double search_s = 5.0;             ///< how long one signal's search lasts (s)
  bool broadcast_arm_reach = true;   ///< `~broadcast_arm_reach` (node default false, play.launch sets true)
  double arm_reach_m = 0.5;          ///< `~arm_reach` (node default 0.4; real sessions ran with 0.5)
  MarkerField field = real_marker_field();  ///< the marker configuration
};

/// The `arm_reach` frame in `sandtray`: x, y = the shoulder's position, z = radius of the reachable disc at the
/// screen's level; rotation = the shoulder's, as the real node leaves it.
struct ArmReachFrame {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();        ///< x, y (m), radius (m)
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< the shoulder frame's orientation
};

/// The localisation node's state: idle, looking, and the held odom→sandtray transform.
class Localiser {
 public:
  /// Said after a successful search.
  static constexpr const char* kFoundSpeech = "I know where I am now!";
  /// Said when a search ran out.
  static constexpr const char* kLostSpeech = "I am lost!";

  /// A node with `settings`, not yet localised.
  explicit Localiser(LocaliserSettings settings = {});

  /// `sandtray/signals/robot_localising` arrived at time `t`: (re)starts a search.
  void on_signal(double t);
  /// True while a search runs.
  bool looking() const { return search_started_.has_value(); }
  /// A camera frame taken at `t` while looking (ignored otherwise): detects the field and, when found, computes
  /// and holds odom→sandtray = `odom_T_camera` × camera→sandtray. Returns true when this frame localised.
  bool on_frame(double t, const cv::Mat& image, const Pinhole& camera, const Eigen::Isometry3d& odom_T_camera);
  /// Time passed to `t`: a search older than `search_s` ends unsuccessfully.
  void tick(double t);

  /// The held odom→sandtray transform (nothing before the first success).
  const std::optional<Eigen::Isometry3d>& odom_T_sandtray() const { return odom_T_sandtray_; }
  /// The field fit of the last successful search.
  const std::optional<FieldPose>& last_fit() const { return last_fit_; }
  /// The `arm_reach` frame for the shoulder at `odom_T_shoulder`: nothing before localisation, without
  /// `broadcast_arm_reach`, or when the shoulder is higher above the screen than the reach ("Too high!").
  std::optional<ArmReachFrame> arm_reach(const Eigen::Isometry3d& odom_T_shoulder) const;
  /// Lines to say (the `speech` topic) since the last call.
  std::vector<std::string> take_speech();
  /// Successful and failed searches so far.
  int successes() const { return successes_; }
  /// Searches that ran out.
  int failures() const { return failures_; }

 private:
  LocaliserSettings settings_;
  std::optional<double> search_started_;
  std::optional<Eigen::Isometry3d> odom_T_sandtray_;
  std::optional<FieldPose> last_fit_;
  std::vector<std::string> speech_;
  int successes_ = 0;
  int failures_ = 0;
  mutable bool warned_too_high_ = false;  // the real node throttles this warning
};

/// Distance between two poses: translation (m) and rotation angle (degrees).
struct PoseError {
  double translation_m = 0;  ///< |t_a − t_b|
  double rotation_deg = 0;   ///< angle of R_a⁻¹ R_b
};

/// How far `estimate` is from `truth`.
PoseError pose_error(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth);

}  // namespace freeplay::localisation
