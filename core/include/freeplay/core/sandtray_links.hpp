#pragma once
// The fixed links of the sandtray's URDF (`sandtray.xacro`, published by `sandtray_publisher`): where the two SR300
// cameras and the environment camera sit in the `sandtray` frame (free-play-sandbox.md §2.4). One table for the
// stage's cameras, the recorder's TF and microphones, and the live graph's TF.

#include <Eigen/Geometry>
#include <array>

namespace freeplay {

/// A fixed URDF joint sandtray → link.
struct UrdfLink {
  const char* frame;    ///< child frame, e.g. "camera_purple_link"
  Eigen::Vector3d xyz;  ///< translation in `sandtray` (m)
  Eigen::Vector3d rpy;  ///< URDF roll, pitch, yaw (rad)

  /// The link's rotation (URDF convention: yaw · pitch · roll about fixed axes).
  Eigen::Quaterniond rotation() const {
    return Eigen::Quaterniond(Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()));
  }
};

/// sandtray → camera_purple_link, camera_yellow_link (the SR300s) and env_camera_link (the Kinect).
inline const std::array<UrdfLink, 3> kSandtrayCameraLinks = {{
    {"camera_purple_link", {-0.108, 0.021, 0.035}, {0, -0.349, -0.785}},
    {"camera_yellow_link", {-0.108, -0.377, 0.035}, {0, -0.349, 0.785}},
    {"env_camera_link", {1.4, -0.15, 0.52}, {0, 0.29, 3.142}},
}};

}  // namespace freeplay
