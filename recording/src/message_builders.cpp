#include "message_builders.hpp"

namespace freeplay::recording::detail {

msg::Quaternion quaternion(const Eigen::Quaterniond& q) {
  msg::Quaternion out;
  out.x = q.x();
  out.y = q.y();
  out.z = q.z();
  out.w = q.w();
  return out;
}

msg::TransformStamped transform(const ros::Time& stamp, const std::string& parent, const std::string& child,
                                const Eigen::Vector3d& xyz, const Eigen::Quaterniond& q) {
  msg::TransformStamped tf;
  tf.header.stamp = stamp;
  tf.header.frame_id = ros_string(parent);
  tf.child_frame_id = ros_string(child);
  tf.transform.translation.x = xyz.x();
  tf.transform.translation.y = xyz.y();
  tf.transform.translation.z = xyz.z();
  tf.transform.rotation = quaternion(q);
  return tf;
}

Eigen::Isometry3d pose_of(const Eigen::Vector3d& xyz, const Eigen::Quaterniond& q) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.toRotationMatrix();
  pose.translation() = xyz;
  return pose;
}

Eigen::Quaterniond yaw_quaternion(double yaw) { return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())); }

msg::Point point(double x, double y, double z) {
  msg::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

}  // namespace freeplay::recording::detail
