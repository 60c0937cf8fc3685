// The robot's nodes on a live ROS 1 graph: what `freeplay robot` reads (TF, /zones, /footprints, interaction events,
// face counts, signals) and sends (/poses fake touches, speech, gaze and pointing targets).
#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <spdlog/spdlog.h>
#include <std_msgs/Char.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include "freeplay/ros/graph.hpp"
#include "master_watch.hpp"

namespace freeplay::ros_graph {

namespace {

bool is_sandtray(const std::string& frame) { return frame == "sandtray" || frame == "/sandtray"; }

std::vector<Polyline> polylines(const visualization_msgs::MarkerArray& array) {
  std::vector<Polyline> out;
  for (const auto& m : array.markers) {
    if (m.action != visualization_msgs::Marker::ADD || m.type != visualization_msgs::Marker::LINE_STRIP) continue;
    Polyline p;
    p.frame = m.header.frame_id;
    p.ns = m.ns;
    p.id = m.id;
    bool finite = true;
    for (const auto& q : m.points) {
      finite = finite && std::isfinite(q.x) && std::isfinite(q.y);
      p.points.push_back({q.x, q.y});
    }
    if (!finite) {
      spdlog::warn("dropped marker '{}' {}: non-finite point", p.ns, p.id);
      continue;
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace

struct RobotGraph::Impl {
  std::optional<ros::NodeHandle> nh;  // renewed with every registration
  ros::Publisher poses, speech, look, point;
  std::vector<ros::Subscriber> subscribers;
  ros::AsyncSpinner spinner{2};
  std::mutex mutex;
  std::map<std::string, Transform> frames;
  RobotView view;
  MasterWatch master;
  int registered_with = 0;  // master.returns() at the last registration

  Impl() {
    connect();
    spinner.start();
  }

  // Subscribes and advertises (again after a master restart).
  void connect() {
    nh.emplace();
    auto& handle = *nh;
    poses = handle.advertise<geometry_msgs::PoseStamped>("/poses", 10);
    speech = handle.advertise<std_msgs::String>("speech", 10);
    look = handle.advertise<geometry_msgs::PointStamped>("freeplay/robot/look_at", 10);
    point = handle.advertise<geometry_msgs::PointStamped>("freeplay/robot/point_at", 10);
    for (const char* topic : {"/tf", "/tf_static"}) {
      subscribers.push_back(handle.subscribe<tf2_msgs::TFMessage>(topic, 100, [this](const auto& msg) { on_tf(*msg); }));
    }
    subscribers.push_back(handle.subscribe<visualization_msgs::MarkerArray>("/zones", 1, [this](const auto& msg) {
      auto zones = polylines(*msg);
      std::lock_guard lock(mutex);
      view.zones = std::move(zones);
    }));
    subscribers.push_back(handle.subscribe<visualization_msgs::MarkerArray>("/footprints", 1, [this](const auto& msg) {
      auto footprints = polylines(*msg);
      std::lock_guard lock(mutex);
      view.footprints = std::move(footprints);
    }));
    subscribers.push_back(handle.subscribe<std_msgs::String>("sandtray/interaction_events", 20, [this](const auto& msg) {
      std::lock_guard lock(mutex);
      view.interaction_events.push_back(msg->data);
    }));
    subscribers.push_back(handle.subscribe<std_msgs::Empty>("sandtray/signals/start_freeplay", 1, [this](const auto&) {
      std::lock_guard lock(mutex);
      view.freeplay_started = true;
    }));
    const char* faces[] = {"/camera_purple/nb_detected_faces", "/camera_yellow/nb_detected_faces"};
    for (std::size_t i = 0; i < 2; ++i) {
      subscribers.push_back(handle.subscribe<std_msgs::Char>(faces[i], 1, [this, i](const auto& msg) {
        std::lock_guard lock(mutex);
        view.faces[i] = msg->data;
      }));
    }
  }

  // After the master came back: drops every registration and makes them anew.
  void maintain() {
    const int returns = master.returns();
    if (returns == registered_with || !master.up()) return;
    registered_with = returns;
    for (auto* p : {&poses, &speech, &look, &point}) p->shutdown();
    for (auto& sub : subscribers) sub.shutdown();
    subscribers.clear();
    nh.reset();
    connect();
    spdlog::info("subscribed and advertised with the ROS master again");
  }

  ~Impl() { spinner.stop(); }

  void on_tf(const tf2_msgs::TFMessage& msg) {
    std::lock_guard lock(mutex);
    for (const auto& t : msg.transforms) {
      if (!is_sandtray(t.header.frame_id)) continue;
      const auto& p = t.transform.translation;
      const auto& q = t.transform.rotation;
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(q.w)) {
        spdlog::warn("/tf: dropped a non-finite transform sandtray → {}", t.child_frame_id);
        continue;
      }
      std::string child = t.child_frame_id;
      if (!child.empty() && child.front() == '/') child.erase(0, 1);
      frames[child] = Transform{"sandtray", child, {p.x, p.y, p.z}, {q.x, q.y, q.z, q.w}, ros::WallTime::now().toSec()};
    }
  }
};

RobotGraph::RobotGraph() : impl_(std::make_unique<Impl>()) {}
RobotGraph::~RobotGraph() = default;

bool RobotGraph::ok() const { return ros::ok(); }

void RobotGraph::maintain() { impl_->maintain(); }

RobotView RobotGraph::take() {
  std::lock_guard lock(impl_->mutex);
  RobotView out = impl_->view;
  impl_->view.interaction_events.clear();
  for (const auto& [name, t] : impl_->frames) out.frames.push_back(t);
  return out;
}

void RobotGraph::finger(double x, double y) {
  geometry_msgs::PoseStamped msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = "/sandtray";
  msg.pose.position.x = x;
  msg.pose.position.y = y;
  impl_->poses.publish(msg);
}

void RobotGraph::speech(const std::string& text) {
  std_msgs::String msg;
  msg.data = text;
  impl_->speech.publish(msg);
}

void RobotGraph::look_at(double x, double y, double z) {
  geometry_msgs::PointStamped msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = "sandtray";
  msg.point.x = x;
  msg.point.y = y;
  msg.point.z = z;
  impl_->look.publish(msg);
}

void RobotGraph::point_at(double x, double y) {
  geometry_msgs::PointStamped msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = "sandtray";
  msg.point.x = x;
  msg.point.y = y;
  impl_->point.publish(msg);
}

}  // namespace freeplay::ros_graph
