#include "freeplay/recording/tick_topics.hpp"

#include <fmt/format.h>
#include <ros/serialization.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "freeplay/planning/occupancy_grid.hpp"
#include "freeplay/recording/robot_links.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/sim/markers.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"
#include "message_builders.hpp"

namespace freeplay::recording {

namespace {

using detail::kCameraLinks;
using detail::point;
using detail::pose_of;
using detail::transform;
using detail::yaw_quaternion;

using Frames = std::vector<std::pair<std::string, Eigen::Isometry3d>>;

// The signal the supervisor sends when a protocol stage starts.
const std::map<std::string, std::string> kStageSignals = {
    {"tutorial", "start_tutorial"}, {"freeplay", "start_freeplay"}, {"debriefing", "blank_interface"}};

constexpr double kFootprintsAfterS = 1.0;  // the game publishes /footprints once, ~1 s after start
constexpr int kMapEveryTicks = 2;          // map_and_plan publishes /map at 5 Hz
constexpr double kTrajectoryLifetimeS = 1.0;  // move_sandbox_items' trajectory marker lives 1 s

ros::Time time_of_ns(std::uint64_t ns) {
  ros::Time stamp;
  stamp.fromNSec(ns);
  return stamp;
}

// The declaration of `topic` carrying messages of type M.
template <class M>
TopicDeclaration declaration_of(std::string topic, bool latched) {
  namespace mt = ros::message_traits;
  return {std::move(topic), mt::DataType<M>::value(), mt::MD5Sum<M>::value(), mt::Definition<M>::value(), latched};
}

// A visualization_msgs/Marker LINE_STRIP of one of the game's line markers.
msg::Marker line_marker(const sim::LineMarker& line, const ros::Time& stamp) {
  msg::Marker m;
  m.header.stamp = stamp;
  m.header.frame_id = ros_string(line.frame);
  m.ns = ros_string(line.ns);
  m.id = line.id;
  m.type = msg::Marker::LINE_STRIP;
  m.action = msg::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = line.width;
  m.color.r = line.rgb[0];
  m.color.g = line.rgb[1];
  m.color.b = line.rgb[2];
  m.color.a = 1.0F;
  for (const auto& v : line.points) m.points.push_back(point(v[0], v[1]));
  return m;
}

}  // namespace

struct TickTopics::Impl {
  TickTopicsOptions options;
  PublisherClocks clocks;
  std::optional<runner::ReachDisc> arm_reach;
  std::unique_ptr<NaoLinkFrames> nao_links;  // made at the first robot snapshot (a kinematic stage)
  std::uint64_t background_version = ~std::uint64_t{0};
  bool footprints_sent = false;
  long state_ticks = 0;
  std::vector<std::array<double, 2>> trajectory;  // the finger's path during the current move

  bool wants(TickStream stream) const { return (options.streams & stream) != 0; }

  ros::Time stamp(double t) const {
    return time_of_ns(options.origin_ns + static_cast<std::uint64_t>(static_cast<std::int64_t>(std::round(t * 1e9))));
  }

  /// One /tf message of `publisher`, stamped when that publisher sends the tick `t`.
  void put_tf(std::vector<TopicMessage>& out, const std::string& publisher, double t, const Frames& frames) {
    const double published = clocks.publish(publisher, t);
    const auto at = stamp(published);
    msg::TFMessage tf;
    for (const auto& [child, pose] : frames) {
      tf.transforms.push_back(transform(at, "sandtray", child, pose.translation(), Eigen::Quaterniond(pose.rotation())));
    }
    out.push_back({topics::kTf, publisher, published, false, std::move(tf)});
  }

  void put_frames(std::vector<TopicMessage>& out, const runner::EpisodeSnapshot& s) {
    const double t = s.t;
    if (wants(kGameFrames)) {  // the game's TF broadcasters: one per item and one per active touch, 10 Hz each
      for (const auto& item : s.tray->items()) {
        put_tf(out, "game/" + item.name, t,
               {{item.name, pose_of({item.pose.x, item.pose.y, 0.0}, yaw_quaternion(item.pose.theta))}});
      }
      for (const auto& touch : s.tray->touches()) {
        const auto name = fmt::format("touch{}", touch.finger);
        put_tf(out, "game/" + name, t,
               {{name, pose_of({touch.position.x(), touch.position.y(), 0.0}, Eigen::Quaterniond::Identity())}});
      }
    }
    if (wants(kCameraLinkFrames)) {  // sandtray_publisher: the URDF camera links
      Frames links;
      for (const auto& link : kCameraLinks) links.emplace_back(link.frame, pose_of(link.xyz, link.rotation()));
      put_tf(out, "sandtray_publisher", t, links);
    }
    if (wants(kHeadTrackers)) {
      for (const auto& child : s.children) {
        const Eigen::Vector3d direction = child.gaze_point - child.head;
        const auto q = direction.norm() > 1e-9 ? Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), direction)
                                                : Eigen::Quaterniond::Identity();
        put_tf(out, "gazr/" + child.seat, t, {{"child_" + child.seat + "_0", pose_of(child.head, q)}});
      }
    }
    if (wants(kRobotFocus) && s.robot != nullptr) {
      put_tf(out, "robot_focus", t, {{"robot_focus", pose_of(s.robot->gaze_point, Eigen::Quaterniond::Identity())}});
    }
  }

  void put_background(std::vector<TopicMessage>& out, double t, const sim::Sandtray& tray) {
    const cv::Mat& bgr = tray.background();
    if (wants(kBackground) || wants(kBackgroundRaw)) {  // the game's ImagePublisher
      const double published = clocks.publish("sandtray/background", t);
      msg::Header header;
      header.stamp = stamp(published);
      header.frame_id = ros_string("sandtray");
      if (wants(kBackground)) {
        msg::CompressedImage image;
        image.header = header;
        image.format = ros_string("rgba8; png compressed bgr8");
        std::vector<std::uint8_t> png;
        cv::imencode(".png", bgr, png, {cv::IMWRITE_PNG_COMPRESSION, options.png_level});
        image.data.assign(png.begin(), png.end());
        out.push_back({topics::kBackground, "sandtray/background", published, true, std::move(image)});
      }
      if (wants(kBackgroundRaw)) {
        msg::Image raw;
        raw.header = header;
        raw.width = static_cast<std::uint32_t>(bgr.cols);
        raw.height = static_cast<std::uint32_t>(bgr.rows);
        raw.encoding = ros_string("rgba8");
        raw.step = raw.width * 4;
        cv::Mat rgba;
        cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
        raw.data.assign(rgba.data, rgba.data + rgba.total() * rgba.elemSize());
        out.push_back({topics::kBackgroundRaw, "sandtray/background", published, true, std::move(raw)});
        msg::CameraInfo info;  // a virtual pinhole: K = [1/pixelscale, 0, w/2; 0, 1/pixelscale, h/2; 0, 0, 1]
        info.header = header;
        info.width = static_cast<std::uint32_t>(bgr.cols);
        info.height = static_cast<std::uint32_t>(bgr.rows);
        info.distortion_model = ros_string("plumb_bob");
        info.D = {0, 0, 0, 0, 0};
        const double f = bgr.cols / sim::kScreenWidthM;
        info.K = {f, 0, bgr.cols / 2.0, 0, f, bgr.rows / 2.0, 0, 0, 1};
        out.push_back({topics::kBackgroundInfo, "sandtray/background", published, true, std::move(info)});
      }
    }
    if (wants(kZones)) {
      const double published = clocks.publish("zones_from_image", t);
      msg::MarkerArray zones;  // zones_from_image: DELETEALL, then one closed LINE_STRIP per contour
      msg::Marker clear;
      clear.header.stamp = stamp(published);
      clear.header.frame_id = ros_string("/sandtray");
      clear.action = msg::Marker::DELETEALL;
      zones.markers.push_back(clear);
      for (const auto& zone : sim::zone_markers(tray)) zones.markers.push_back(line_marker(zone, clear.header.stamp));
      out.push_back({topics::kZones, "zones_from_image", published, true, std::move(zones)});
    }
  }

  void put_footprints(std::vector<TopicMessage>& out, double t, const sim::Sandtray& tray) {
    msg::MarkerArray footprints;  // FootprintsPublisher: one closed polygon per item, in the item's frame
    const double published = clocks.publish("footprints", t);
    for (const auto& item : sim::footprint_markers(tray)) footprints.markers.push_back(line_marker(item, stamp(published)));
    out.push_back({topics::kFootprints, "footprints", published, true, std::move(footprints)});
  }

  void put_robot(std::vector<TopicMessage>& out, double t, const runner::RobotSnapshot& robot) {
    if (wants(kJointStates)) {
      msg::JointState joints;
      const double published = clocks.publish("naoqi_driver/joint_states", t);
      joints.header.stamp = stamp(published);
      for (const auto& name : robot.joint_names) joints.name.push_back(ros_string(name));
      joints.position.assign(robot.positions.begin(), robot.positions.end());
      joints.velocity.assign(robot.velocities.begin(), robot.velocities.end());
      joints.effort.assign(robot.efforts.begin(), robot.efforts.end());
      out.push_back({topics::kJointStates, "naoqi_driver/joint_states", published, false, std::move(joints)});
    }
    if (wants(kRobotLinks)) {  // robot_state_publisher: the URDF links from the joint states, at the /tf rate
      if (!nao_links) nao_links = std::make_unique<NaoLinkFrames>(options.arm_reach_m);
      const double published = clocks.publish("robot_state_publisher", t);
      msg::TFMessage links;
      for (const auto& link : nao_links->compute(robot.joint_names, robot.positions)) {
        links.transforms.push_back(transform(stamp(published), link.parent, link.child, link.parent_T_child.translation(),
                                             Eigen::Quaterniond(link.parent_T_child.rotation())));
      }
      out.push_back({topics::kTf, "robot_state_publisher", published, false, std::move(links)});
    }
    if (!robot.finger) {
      trajectory.clear();
      return;
    }
    if (!wants(kFingerPoses) && !wants(kTrajectory)) return;
    const double published = clocks.publish("move_sandbox_items", t);  // /poses at 10 Hz during a move
    if (wants(kFingerPoses)) {
      msg::PoseStamped pose;
      pose.header.stamp = stamp(published);
      pose.header.frame_id = ros_string("sandtray");
      pose.pose.position = point(robot.finger->x(), robot.finger->y());
      pose.pose.orientation.w = 1.0;
      out.push_back({topics::kPoses, "move_sandbox_items", published, false, std::move(pose)});
    }
    if (wants(kTrajectory)) {  // ns item_motion_traj, LINE_STRIP, width 0.01, red, lifetime 1 s
      trajectory.push_back({robot.finger->x(), robot.finger->y()});
      const sim::LineMarker line{"/sandtray", "item_motion_traj", 0, trajectory, {1.F, 0.F, 0.F}, 0.01};
      auto marker = line_marker(line, stamp(published));
      marker.lifetime = ros::Duration(kTrajectoryLifetimeS);
      out.push_back({topics::kTrajectory, "move_sandbox_items", published, false, std::move(marker)});
    }
  }

  void put_map(std::vector<TopicMessage>& out, double t, const sim::Sandtray& tray) {
    using planning::OccupancyGrid;  // map_and_plan: the occupancy grid of every footprint (nothing inhibited)
    const double published = clocks.publish("map_and_plan", t);
    const auto grid = OccupancyGrid::build(runner::sandtray_move_world(tray).footprints(), "");
    msg::OccupancyGrid map;
    map.header.stamp = stamp(published);
    map.header.frame_id = ros_string("/sandtray");
    map.info.map_load_time = map.header.stamp;
    map.info.resolution = static_cast<float>(OccupancyGrid::kResolutionM);
    map.info.width = static_cast<std::uint32_t>(OccupancyGrid::kCols);
    map.info.height = static_cast<std::uint32_t>(OccupancyGrid::kRows);
    map.info.origin.position.y = -OccupancyGrid::kHeightM;
    map.info.origin.orientation.w = 1.0;
    map.data.resize(static_cast<std::size_t>(OccupancyGrid::kCols * OccupancyGrid::kRows));
    for (int row = 0; row < OccupancyGrid::kRows; ++row) {  // OccupancyGrid rows run along −y; ROS rows from origin y
      for (int col = 0; col < OccupancyGrid::kCols; ++col) {
        map.data[static_cast<std::size_t>((OccupancyGrid::kRows - 1 - row) * OccupancyGrid::kCols + col)] =
            static_cast<std::int8_t>(grid.occupancy({col, row}));
      }
    }
    out.push_back({topics::kMap, "map_and_plan", published, false, std::move(map)});
  }

  void put_state(std::vector<TopicMessage>& out, const runner::EpisodeSnapshot& s) {
    const double t = s.t;
    const sim::Sandtray& tray = *s.tray;
    if (tray.background_version() != background_version) {  // the game polls its drawing every 250 ms itself
      background_version = tray.background_version();
      put_background(out, t, tray);
    }
    if (wants(kFootprints) && !footprints_sent && t >= kFootprintsAfterS - 1e-9) {
      footprints_sent = true;
      put_footprints(out, t, tray);
    }
    if (s.robot != nullptr) put_robot(out, t, *s.robot);
    if (wants(kMap) && state_ticks % kMapEveryTicks == 0) put_map(out, t, tray);
    ++state_ticks;
    if (wants(kArmReach) && arm_reach) {  // x, y: the shoulder on the table; z: radius of the reachable disc
      put_tf(out, "sandtray_localisation/arm_reach", t,
             {{"arm_reach", pose_of({arm_reach->centre.x(), arm_reach->centre.y(), arm_reach->radius},
                                    Eigen::Quaterniond::Identity())}});
    }
  }
};

TickTopics::TickTopics(std::uint64_t seed, TickTopicsOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->clocks = PublisherClocks(seed);
}

TickTopics::~TickTopics() = default;
TickTopics::TickTopics(TickTopics&& other) noexcept = default;
TickTopics& TickTopics::operator=(TickTopics&& other) noexcept = default;

std::vector<TopicMessage> TickTopics::frames(const runner::EpisodeSnapshot& snapshot) {
  std::vector<TopicMessage> out;
  if (snapshot.tray != nullptr) impl_->put_frames(out, snapshot);
  return out;
}

std::vector<TopicMessage> TickTopics::state(const runner::EpisodeSnapshot& snapshot) {
  std::vector<TopicMessage> out;
  if (snapshot.tray != nullptr) impl_->put_state(out, snapshot);
  return out;
}

std::vector<TopicMessage> TickTopics::tick(const runner::EpisodeSnapshot& snapshot) {
  auto out = frames(snapshot);
  for (auto& m : state(snapshot)) out.push_back(std::move(m));
  std::stable_sort(out.begin(), out.end(),
                   [](const TopicMessage& a, const TopicMessage& b) { return a.published < b.published; });
  return out;
}

std::vector<TopicMessage> TickTopics::event(double t, const Event& e) const {
  std::vector<TopicMessage> out;
  if (!impl_->wants(kEventTopics)) return out;
  if (const auto* interaction = e.get<events::InteractionEvent>()) {
    msg::String message;
    message.data = ros_string(interaction->message);
    out.push_back({topics::kInteractionEvents, "game", t, false, std::move(message)});
  } else if (const auto* say = e.get<events::Say>(); say && e.source == "robot") {
    msg::String speech;
    speech.data = ros_string(say->text);
    out.push_back({topics::kSpeech, "robot", t, false, std::move(speech)});
  } else if (const auto* stage = e.get<events::Stage>(); stage && e.source == "protocol") {
    if (const auto it = kStageSignals.find(stage->stage); it != kStageSignals.end()) {
      out.push_back({topics::kSignalsPrefix + it->second, "supervisor", t, false, msg::Empty()});
    }
  }
  return out;
}

void TickTopics::set_arm_reach(const std::optional<runner::ReachDisc>& reach) { impl_->arm_reach = reach; }

std::uint64_t TickTopics::stamp_ns(double t) const { return impl_->stamp(t).toNSec(); }

std::vector<TopicDeclaration> declared_topics(unsigned streams) {
  std::vector<TopicDeclaration> out;
  const auto declare = [&](unsigned of, const char* topic, auto message, bool latched) {
    if ((streams & of) != 0) out.push_back(declaration_of<decltype(message)>(topic, latched));
  };
  declare(kGameFrames | kCameraLinkFrames | kHeadTrackers | kRobotFocus | kRobotLinks | kArmReach, topics::kTf,
          msg::TFMessage(), false);
  declare(kZones, topics::kZones, msg::MarkerArray(), true);
  declare(kFootprints, topics::kFootprints, msg::MarkerArray(), true);
  declare(kBackground, topics::kBackground, msg::CompressedImage(), true);
  declare(kBackgroundRaw, topics::kBackgroundRaw, msg::Image(), true);
  declare(kBackgroundRaw, topics::kBackgroundInfo, msg::CameraInfo(), true);
  declare(kJointStates, topics::kJointStates, msg::JointState(), false);
  declare(kFingerPoses, topics::kPoses, msg::PoseStamped(), false);
  declare(kTrajectory, topics::kTrajectory, msg::Marker(), false);
  declare(kMap, topics::kMap, msg::OccupancyGrid(), false);
  declare(kEventTopics, topics::kInteractionEvents, msg::String(), false);
  declare(kEventTopics, topics::kSpeech, msg::String(), false);
  for (const auto& [stage, signal] : kStageSignals) {
    declare(kEventTopics, (std::string(topics::kSignalsPrefix) + signal).c_str(), msg::Empty(), false);
  }
  return out;
}

SerializedTopicMessage serialize(const TopicMessage& message, std::uint64_t origin_ns) {
  return std::visit(
      [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        auto bytes = std::make_shared<std::vector<std::uint8_t>>(ros::serialization::serializationLength(m));
        ros::serialization::OStream stream(bytes->data(), static_cast<std::uint32_t>(bytes->size()));
        ros::serialization::serialize(stream, m);
        const auto offset = static_cast<std::int64_t>(std::round(message.published * 1e9));
        return SerializedTopicMessage{declaration_of<M>(message.topic, message.latched),
                                      origin_ns + static_cast<std::uint64_t>(offset), std::move(bytes)};
      },
      message.message);
}

}  // namespace freeplay::recording
