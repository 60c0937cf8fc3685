#include "freeplay/web/foxglove.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <ros/serialization.h>

#include "freeplay/recording/camera_topics.hpp"
#include "freeplay/recording/robot_links.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::web {

namespace {

namespace msg = recording::msg;

template <typename Message>
FoxgloveChannel channel(int id, const std::string& topic) {
  return {id, topic, ros::message_traits::DataType<Message>::value(), ros::message_traits::Definition<Message>::value()};
}

template <typename Message>
FoxgloveMessage message(int channel_id, std::uint64_t stamp_ns, const Message& m) {
  std::string bytes(ros::serialization::serializationLength(m), '\0');
  ros::serialization::OStream stream(reinterpret_cast<std::uint8_t*>(bytes.data()), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(stream, m);
  return {channel_id, stamp_ns, std::make_shared<const std::string>(std::move(bytes))};
}

ros::Time stamp_of(std::uint64_t ns) {
  ros::Time t;
  t.fromNSec(ns);
  return t;
}

msg::TransformStamped planar(const ros::Time& stamp, const std::string& child, double x, double y, double yaw) {
  msg::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = recording::ros_string("sandtray");
  t.child_frame_id = recording::ros_string(child);
  t.transform.translation.x = x;
  t.transform.translation.y = y;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  return t;
}

msg::Marker line_strip(const ros::Time& stamp, const std::string& frame, const std::string& ns, int id,
                       const Polygon2& polygon, std::array<float, 3> rgb) {
  msg::Marker m;
  m.header.stamp = stamp;
  m.header.frame_id = recording::ros_string(frame);
  m.ns = recording::ros_string(ns);
  m.id = id;
  m.type = msg::Marker::LINE_STRIP;
  m.action = msg::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = 0.002;
  m.color.r = rgb[0];
  m.color.g = rgb[1];
  m.color.b = rgb[2];
  m.color.a = 1.0F;
  for (std::size_t i = 0; i <= polygon.size() && !polygon.empty(); ++i) {  // closed: the first point again
    msg::Point p;
    p.x = polygon[i % polygon.size()].x();
    p.y = polygon[i % polygon.size()].y();
    m.points.push_back(p);
  }
  return m;
}

}  // namespace

const std::vector<FoxgloveChannel>& foxglove_channels() {
  static const std::vector<FoxgloveChannel> kChannels = {
      channel<msg::TFMessage>(kFoxgloveTf, "/tf"),
      channel<msg::MarkerArray>(kFoxgloveZones, "/zones"),
      channel<msg::MarkerArray>(kFoxgloveFootprints, "/footprints"),
      channel<msg::CompressedImage>(kFoxgloveBackground, "/sandtray/background/image/compressed")};
  return kChannels;
}

std::vector<FoxgloveChannel> foxglove_channels(const std::vector<std::string>& cameras, bool robot) {
  auto out = foxglove_channels();
  if (robot) out.push_back(channel<msg::JointState>(kFoxgloveJointStates, "/joint_states"));
  int id = kFoxgloveFirstCamera;
  for (const auto& name : cameras) {
    const auto topic = recording::camera_topics(name).rgb_image;
    out.push_back(channel<msg::CompressedImage>(id++, topic.starts_with('/') ? topic : fmt::format("/{}", topic)));
  }
  return out;
}

FoxgloveMessage foxglove_robot_tf(const std::vector<recording::LinkTransform>& links, std::uint64_t stamp_ns) {
  const auto stamp = stamp_of(stamp_ns);
  msg::TFMessage tf;
  for (const auto& link : links) {
    msg::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = recording::ros_string(link.parent);
    t.child_frame_id = recording::ros_string(link.child);
    const Eigen::Vector3d p = link.parent_T_child.translation();
    const Eigen::Quaterniond q(link.parent_T_child.rotation());
    t.transform.translation.x = p.x();
    t.transform.translation.y = p.y();
    t.transform.translation.z = p.z();
    t.transform.rotation.x = q.x();
    t.transform.rotation.y = q.y();
    t.transform.rotation.z = q.z();
    t.transform.rotation.w = q.w();
    tf.transforms.push_back(std::move(t));
  }
  return message(kFoxgloveTf, stamp_ns, tf);
}

FoxgloveMessage foxglove_joint_states(const runner::RobotSnapshot& robot, std::uint64_t stamp_ns) {
  msg::JointState joints;
  joints.header.stamp = stamp_of(stamp_ns);
  for (const auto& name : robot.joint_names) joints.name.push_back(recording::ros_string(name));
  joints.position.assign(robot.positions.begin(), robot.positions.end());
  joints.velocity.assign(robot.velocities.begin(), robot.velocities.end());
  joints.effort.assign(robot.efforts.begin(), robot.efforts.end());
  return message(kFoxgloveJointStates, stamp_ns, joints);
}

FoxgloveMessage foxglove_camera(int channel_id, const std::string& frame_id, const std::vector<std::uint8_t>& jpeg,
                                std::uint64_t stamp_ns) {
  msg::CompressedImage image;
  image.header.stamp = stamp_of(stamp_ns);
  image.header.frame_id = recording::ros_string(frame_id);
  image.format = recording::ros_string("jpeg");
  image.data.assign(jpeg.begin(), jpeg.end());
  return message(channel_id, stamp_ns, image);
}

FoxgloveMessage foxglove_tf(const sim::Sandtray& tray, std::uint64_t stamp_ns) {
  const auto stamp = stamp_of(stamp_ns);
  msg::TFMessage tf;
  for (const auto& item : tray.items()) tf.transforms.push_back(planar(stamp, item.name, item.pose.x, item.pose.y, item.pose.theta));
  for (const auto& touch : tray.touches()) {
    tf.transforms.push_back(planar(stamp, "touch" + std::to_string(touch.finger), touch.position.x(), touch.position.y(), 0.0));
  }
  return message(kFoxgloveTf, stamp_ns, tf);
}

FoxgloveMessage foxglove_zones(const sim::Sandtray& tray, std::uint64_t stamp_ns) {
  const auto stamp = stamp_of(stamp_ns);
  msg::MarkerArray zones;
  for (const auto& zone : tray.zones().zones()) {
    const auto rgb = sim::zone_marker_rgb(zone.colour);
    zones.markers.push_back(line_strip(stamp, "sandtray", "sandbox_zone_" + zone.colour, zone.id, zone.polygon,
                                       {rgb[0] / 255.F, rgb[1] / 255.F, rgb[2] / 255.F}));
  }
  return message(kFoxgloveZones, stamp_ns, zones);
}

FoxgloveMessage foxglove_footprints(const sim::Sandtray& tray, std::uint64_t stamp_ns) {
  const auto stamp = stamp_of(stamp_ns);
  msg::MarkerArray footprints;
  int id = 0;
  for (const auto& [name, polygon] : tray.published_footprints()) {
    footprints.markers.push_back(line_strip(stamp, name, name, id++, polygon, {0.F, 1.F, 0.F}));
  }
  return message(kFoxgloveFootprints, stamp_ns, footprints);
}

FoxgloveMessage foxglove_background(const std::string& jpeg, std::uint64_t stamp_ns) {
  msg::CompressedImage image;
  image.header.stamp = stamp_of(stamp_ns);
  image.header.frame_id = recording::ros_string("sandtray");
  image.format = recording::ros_string("jpeg");
  image.data.assign(jpeg.begin(), jpeg.end());
  return message(kFoxgloveBackground, stamp_ns, image);
}

std::string foxglove_frame(std::uint32_t subscription, const FoxgloveMessage& message) {
  std::string frame(1 + 4 + 8, '\0');
  frame[0] = 0x01;  // message data
  for (int i = 0; i < 4; ++i) frame[static_cast<std::size_t>(1 + i)] = static_cast<char>((subscription >> (8 * i)) & 0xFF);
  for (int i = 0; i < 8; ++i) frame[static_cast<std::size_t>(5 + i)] = static_cast<char>((message.stamp_ns >> (8 * i)) & 0xFF);
  return frame + *message.payload;
}

}  // namespace freeplay::web
