#pragma once
// Geometry message builders shared by the recorder's publishers (internal to freeplay_recording).

#include <Eigen/Geometry>
#include <string>

#include "freeplay/core/sandtray_links.hpp"
#include "freeplay/recording/ros_messages.hpp"

namespace freeplay::recording::detail {

/// A fixed URDF joint sandtray → link: xyz, rpy.
using StaticLink = UrdfLink;
/// The URDF joints sandtray → camera links (free-play-sandbox.md §2.4).
inline const auto& kCameraLinks = kSandtrayCameraLinks;

/// geometry_msgs/Quaternion of `q`.
msg::Quaternion quaternion(const Eigen::Quaterniond& q);
/// A TransformStamped `parent` → `child`.
msg::TransformStamped transform(const ros::Time& stamp, const std::string& parent, const std::string& child,
                                const Eigen::Vector3d& xyz, const Eigen::Quaterniond& q);
/// The isometry of a translation and rotation.
Eigen::Isometry3d pose_of(const Eigen::Vector3d& xyz, const Eigen::Quaterniond& q);
/// A rotation about z.
Eigen::Quaterniond yaw_quaternion(double yaw);
/// geometry_msgs/Point.
msg::Point point(double x, double y, double z = 0.0);

}  // namespace freeplay::recording::detail
