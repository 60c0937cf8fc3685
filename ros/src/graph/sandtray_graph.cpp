// The sandtray game and core nodes on a live ROS 1 graph: every topic, latch and server of the real `sandtray`,
// `map_and_plan`, `move_sandbox_items` and `sandbox_zones_from_image` nodes, as plain data for `freeplay serve`.
#include <actionlib/server/action_server.h>
#include <freeplay_sandbox_msgs/PlaygroundNavigationAction.h>
#include <freeplay_sandbox_msgs/PlaygroundPlan.h>
#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <spdlog/spdlog.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <chrono>
#include <cstring>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <utility>

#include "freeplay/ros/graph.hpp"
#include "master_watch.hpp"

namespace freeplay::ros_graph {
namespace {
/// A message already serialised: roscpp sends its bytes as they are, with the type it names.
struct RawMessage {
  const SerializedMessage* message = nullptr;  ///< the bytes and their type
};
}  // namespace
}  // namespace freeplay::ros_graph

namespace ros::message_traits {
/// The type's MD5 sum travels with the message.
template <>
struct MD5Sum<freeplay::ros_graph::RawMessage> {
  static const char* value() { return "*"; }
  static const char* value(const freeplay::ros_graph::RawMessage& m) { return m.message->md5sum.c_str(); }
};
/// The type's name travels with the message.
template <>
struct DataType<freeplay::ros_graph::RawMessage> {
  static const char* value() { return "*"; }
  static const char* value(const freeplay::ros_graph::RawMessage& m) { return m.message->datatype.c_str(); }
};
/// The type's definition travels with the message.
template <>
struct Definition<freeplay::ros_graph::RawMessage> {
  static const char* value() { return ""; }
  static const char* value(const freeplay::ros_graph::RawMessage& m) { return m.message->definition.c_str(); }
};
}  // namespace ros::message_traits

namespace ros::serialization {
/// Writes the serialised bytes unchanged.
template <>
struct Serializer<freeplay::ros_graph::RawMessage> {
  /// Copies the bytes into the stream.
  template <typename Stream>
  static void write(Stream& stream, const freeplay::ros_graph::RawMessage& m) {
    const auto& bytes = *m.message->bytes;
    if (!bytes.empty()) std::memcpy(stream.advance(static_cast<std::uint32_t>(bytes.size())), bytes.data(), bytes.size());
  }
  /// The number of bytes.
  static std::uint32_t serializedLength(const freeplay::ros_graph::RawMessage& m) {
    return static_cast<std::uint32_t>(m.message->bytes->size());
  }
};
}  // namespace ros::serialization

namespace freeplay::ros_graph {

namespace {

using NavigationServer = actionlib::ActionServer<freeplay_sandbox_msgs::PlaygroundNavigationAction>;

// Every signal of the game (§2.2): published by the game, the supervisor or both.
const char* const kSignals[] = {"start_visual_tracking", "start_tutorial", "start_items_placement", "start_freeplay",
                                "blank_interface", "clear_drawing", "shuffle_items", "items_to_stash",
                                "robot_localising", "background_drawing", "visual_tracking_calibration_started",
                                "visual_tracking_calibration_ended"};
constexpr double kPlanAnswerTimeoutS = 2.0;

ros::Time stamp_of(double t) { return ros::Time(t); }

// A gaze or pointing target in `sandtray` with a finite point; anything else is logged and dropped.
bool valid_target(const geometry_msgs::PointStamped& m, const char* topic) {
  const auto& p = m.point;
  const std::string frame = m.header.frame_id;
  if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && (frame == "sandtray" || frame == "/sandtray")) {
    return true;
  }
  spdlog::warn("{}: dropped a malformed target (frame '{}', {} {} {}; expected frame sandtray and a finite point)",
               topic, frame, p.x, p.y, p.z);
  return false;
}

// True for a message this node published: intra-process delivery carries no connection header.
bool own(const std::string& publisher) {
  return publisher == ros::this_node::getName() || publisher == "unknown_publisher";
}

}  // namespace

struct SandtrayGraph::Impl {
  NodeOptions options;
  std::optional<ros::NodeHandle> nh;  // renewed with every registration
  ros::Publisher clock, tf, speech, poses;
  std::map<std::string, ros::Publisher> topics;  // by topic, advertised at the first message (publish)
  std::map<std::string, SerializedMessage> latched;  // the latched topics' last messages, sent again after a restart
  std::vector<SerializedMessage> declared;           // topics advertised up front (advertise), again after a restart
  std::map<std::string, ros::Publisher> signal_out;  // every signal advertised (the stages' go out through publish)
  std::map<std::string, ros::Publisher> cameras;  // by topic, advertised at the first frame
  std::vector<ros::Subscriber> subscribers;
  std::unique_ptr<NavigationServer> server;
  ros::ServiceServer plan_server;
  ros::AsyncSpinner spinner{4};
  MasterWatch master;
  int registered_with = 0;  // master.returns() at the last registration
  mutable std::mutex mutex;
  std::condition_variable answered;
  std::deque<FingerPose> poses_in;
  std::deque<std::string> signals_in;
  std::optional<std::array<double, 3>> look_at;
  std::optional<std::array<double, 2>> point_at;
  std::uint64_t next_id = 1;
  std::map<std::uint64_t, NavigationServer::GoalHandle> goals;  // accepted, not yet ended
  std::map<std::uint64_t, bool> cancels;
  std::optional<MoveGoal> pending_goal;
  std::deque<PlanRequest> plan_requests;
  std::map<std::uint64_t, std::optional<std::vector<std::array<double, 2>>>> plan_answers;

  explicit Impl(const NodeOptions& o) : options(o) {
    connect();
    spinner.start();
  }

  // Advertises every topic and server and subscribes (again after a master restart).
  void connect() {
    const NodeOptions& o = options;
    nh.emplace();
    auto& handle = *nh;
    if (o.publish_clock) clock = handle.advertise<rosgraph_msgs::Clock>("/clock", 10);
    tf = handle.advertise<tf2_msgs::TFMessage>("/tf", 100);
    speech = handle.advertise<std_msgs::String>("speech", 10);
    poses = handle.advertise<geometry_msgs::PoseStamped>("/poses", 10);
    for (const auto& declaration : declared) publisher_of(declaration);
    for (const char* name : kSignals) {
      const std::string topic = std::string("sandtray/signals/") + name;
      signal_out[name] = handle.advertise<std_msgs::Empty>(topic, 1);
      subscribers.push_back(subscribe_events<std_msgs::Empty>(
          topic, 10, [this, n = std::string(name)](const ros::MessageEvent<const std_msgs::Empty>& e) {
            if (own(e.getPublisherName())) return;
            std::lock_guard lock(mutex);
            signals_in.push_back(n);
          }));
    }
    subscribers.push_back(subscribe_events<geometry_msgs::PoseStamped>(
        "/poses", 10, [this](const ros::MessageEvent<const geometry_msgs::PoseStamped>& e) { on_pose(e); }));
    subscribers.push_back(handle.subscribe<geometry_msgs::PointStamped>(
        "freeplay/robot/look_at", 10, [this](const geometry_msgs::PointStamped::ConstPtr& m) {
          if (!valid_target(*m, "freeplay/robot/look_at")) return;
          std::lock_guard lock(mutex);
          look_at = std::array<double, 3>{m->point.x, m->point.y, m->point.z};
        }));
    subscribers.push_back(handle.subscribe<geometry_msgs::PointStamped>(
        "freeplay/robot/point_at", 10, [this](const geometry_msgs::PointStamped::ConstPtr& m) {
          if (!valid_target(*m, "freeplay/robot/point_at")) return;
          std::lock_guard lock(mutex);
          point_at = std::array<double, 2>{m->point.x, m->point.y};
        }));
    if (o.core_servers) {
      server = std::make_unique<NavigationServer>(
          handle, "move_sandbox_items", [this](NavigationServer::GoalHandle gh) { on_goal(gh); },
          [this](NavigationServer::GoalHandle gh) { on_cancel(gh); }, false);
      server->start();
      plan_server = handle.advertiseService<freeplay_sandbox_msgs::PlaygroundPlan::Request,
                                        freeplay_sandbox_msgs::PlaygroundPlan::Response>(
          "plan_motion", [this](auto& request, auto& response) { return on_plan(request, response); });
    }
  }

  // Ends every registration (the accepted goals are aborted: their server goes).
  void disconnect() {
    {
      std::lock_guard lock(mutex);
      for (auto& [id, gh] : goals) gh.setAborted({}, "the ROS master restarted");
      goals.clear();
      cancels.clear();
      pending_goal.reset();
    }
    for (auto* p : {&clock, &tf, &speech, &poses}) p->shutdown();
    for (auto& [topic, p] : topics) p.shutdown();
    topics.clear();
    for (auto& [name, p] : signal_out) p.shutdown();
    signal_out.clear();
    for (auto& [name, p] : cameras) p.shutdown();
    cameras.clear();
    for (auto& sub : subscribers) sub.shutdown();
    subscribers.clear();
    server.reset();
    plan_server.shutdown();
    nh.reset();
  }

  // After the master came back: register anew and publish the latched topics again.
  void maintain() {
    const int returns = master.returns();
    if (returns == registered_with || !master.up()) return;
    registered_with = returns;
    disconnect();
    connect();
    for (const auto& [topic, message] : latched) send(message);
    spdlog::info("registered every topic and server with the ROS master again");
  }

  // The publisher of the topic `message` names, advertised on first use.
  ros::Publisher& publisher_of(const SerializedMessage& message) {
    auto it = topics.find(message.topic);
    if (it == topics.end()) {
      const std::uint32_t queue = message.latched ? 1 : message.topic == "/tf" ? 100 : 10;
      ros::AdvertiseOptions advertise(message.topic, queue, message.md5sum, message.datatype, message.definition);
      advertise.latch = message.latched;
      it = topics.emplace(message.topic, nh->advertise(advertise)).first;
    }
    return it->second;
  }

  // Publishes `message` as it is.
  void send(const SerializedMessage& message) { publisher_of(message).publish(RawMessage{&message}); }

  // Subscribes with the sender's connection header (a plain message callback loses the caller id).
  template <class M>
  ros::Subscriber subscribe_events(const std::string& topic, std::uint32_t queue,
                                   const boost::function<void(const ros::MessageEvent<const M>&)>& callback) {
    ros::SubscribeOptions subscription;
    subscription.template initByFullCallbackType<const ros::MessageEvent<const M>&>(topic, queue, callback);
    return nh->subscribe(subscription);
  }

  ~Impl() {
    spinner.stop();
    std::lock_guard lock(mutex);
    for (auto& [id, gh] : goals) gh.setAborted({}, "freeplay serve stopped");
    goals.clear();
  }

  void on_pose(const ros::MessageEvent<const geometry_msgs::PoseStamped>& e) {
    if (own(e.getPublisherName())) return;  // our own executor's stream
    const auto& msg = *e.getMessage();
    const auto& p = msg.pose.position;
    const std::string frame = msg.header.frame_id;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || (frame != "sandtray" && frame != "/sandtray")) {
      spdlog::warn("/poses from {}: dropped a malformed pose (frame '{}', x {}, y {}; expected frame sandtray and a "
                   "finite point)", e.getPublisherName(), frame, p.x, p.y);
      return;
    }
    std::lock_guard lock(mutex);
    poses_in.push_back({p.x, p.y, frame, e.getPublisherName()});
  }

  void on_goal(NavigationServer::GoalHandle gh) {
    const auto goal = gh.getGoal();
    gh.setAccepted();
    std::lock_guard lock(mutex);
    const std::uint64_t id = next_id++;
    if (pending_goal) {  // a newer goal replaces one the sandtray has not taken yet
      auto it = goals.find(pending_goal->id);
      if (it != goals.end()) {
        it->second.setCanceled({}, "preempted by a newer goal");
        goals.erase(it);
      }
    }
    goals[id] = gh;
    pending_goal = MoveGoal{id, goal->item, goal->goal.x, goal->goal.y, goal->goal.z};
  }

  void on_cancel(NavigationServer::GoalHandle gh) {
    std::lock_guard lock(mutex);
    for (const auto& [id, handle] : goals) {
      if (handle == gh) cancels[id] = true;
    }
  }

  bool on_plan(freeplay_sandbox_msgs::PlaygroundPlan::Request& request,
               freeplay_sandbox_msgs::PlaygroundPlan::Response& response) {
    std::unique_lock lock(mutex);
    const std::uint64_t id = next_id++;
    plan_requests.push_back({id, request.goal.header.frame_id, request.goal.pose.position.x,
                             request.goal.pose.position.y});
    plan_answers[id] = std::nullopt;
    const bool got = answered.wait_for(lock, std::chrono::duration<double>(kPlanAnswerTimeoutS),
                                       [&] { return plan_answers[id].has_value() || !ros::ok(); });
    auto answer = std::move(plan_answers[id]);
    plan_answers.erase(id);
    if (!got || !answer) return false;
    response.path.header.frame_id = "/sandtray";
    response.path.header.stamp = ros::Time::now();
    for (std::size_t i = 0; i < answer->size(); ++i) {
      geometry_msgs::PoseStamped pose;
      pose.header.frame_id = "/sandtray";
      pose.header.stamp = ros::Time(0.1 * static_cast<double>(i));  // relative times, as map_and_plan
      pose.pose.position.x = (*answer)[i][0];
      pose.pose.position.y = (*answer)[i][1];
      response.path.poses.push_back(pose);
    }
    return true;
  }
};

SandtrayGraph::SandtrayGraph(const NodeOptions& options) : impl_(std::make_unique<Impl>(options)) {}
SandtrayGraph::~SandtrayGraph() = default;

bool SandtrayGraph::ok() const { return ros::ok(); }

void SandtrayGraph::maintain() { impl_->maintain(); }

void SandtrayGraph::clock(double stamp) {
  if (!impl_->options.publish_clock) return;
  rosgraph_msgs::Clock msg;
  msg.clock = stamp_of(stamp);
  impl_->clock.publish(msg);
}

void SandtrayGraph::advertise(const SerializedMessage& declaration) {
  impl_->declared.push_back(declaration);
  impl_->publisher_of(declaration);
}

void SandtrayGraph::publish(const SerializedMessage& message) {
  impl_->send(message);
  if (message.latched) impl_->latched[message.topic] = message;
}

void SandtrayGraph::tf(double stamp, const std::vector<Transform>& transforms) {
  tf2_msgs::TFMessage msg;
  for (const auto& t : transforms) {
    geometry_msgs::TransformStamped ts;
    ts.header.stamp = stamp_of(stamp);
    ts.header.frame_id = t.parent;
    ts.child_frame_id = t.child;
    ts.transform.translation.x = t.translation[0];
    ts.transform.translation.y = t.translation[1];
    ts.transform.translation.z = t.translation[2];
    ts.transform.rotation.x = t.rotation[0];
    ts.transform.rotation.y = t.rotation[1];
    ts.transform.rotation.z = t.rotation[2];
    ts.transform.rotation.w = t.rotation[3];
    msg.transforms.push_back(ts);
  }
  impl_->tf.publish(msg);
}

void SandtrayGraph::speech(const std::string& text) {
  std_msgs::String msg;
  msg.data = text;
  impl_->speech.publish(msg);
}

void SandtrayGraph::finger(double stamp, double x, double y) {
  geometry_msgs::PoseStamped msg;  // as move_sandbox_items: frame "/sandtray", orientation left all zeros
  msg.header.stamp = stamp_of(stamp);
  msg.header.frame_id = "/sandtray";
  msg.pose.position.x = x;
  msg.pose.position.y = y;
  impl_->poses.publish(msg);
}

void SandtrayGraph::camera(double stamp, const CameraFrame& frame) {
  auto& d = *impl_;
  auto publisher = [&d](const std::string& topic, auto message_type) -> ros::Publisher& {
    auto it = d.cameras.find(topic);
    if (it == d.cameras.end()) {
      it = d.cameras.emplace(topic, d.nh->advertise<decltype(message_type)>(topic, 2)).first;
    }
    return it->second;
  };
  sensor_msgs::CompressedImage image;
  image.header.stamp = stamp_of(stamp);
  image.header.frame_id = frame.frame_id;
  image.format = frame.format;
  image.data = frame.jpeg;
  publisher(frame.image_topic, sensor_msgs::CompressedImage{}).publish(image);
  sensor_msgs::CameraInfo info;
  info.header = image.header;
  info.width = static_cast<std::uint32_t>(frame.width);
  info.height = static_cast<std::uint32_t>(frame.height);
  info.distortion_model = "plumb_bob";
  info.D = {0, 0, 0, 0, 0};
  info.K = {frame.K[0], 0, frame.K[2], 0, frame.K[1], frame.K[3], 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {frame.K[0], 0, frame.K[2], 0, 0, frame.K[1], frame.K[3], 0, 0, 0, 1, 0};
  publisher(frame.info_topic, sensor_msgs::CameraInfo{}).publish(info);
}

std::vector<FingerPose> SandtrayGraph::take_poses() {
  std::lock_guard lock(impl_->mutex);
  std::vector<FingerPose> out(impl_->poses_in.begin(), impl_->poses_in.end());
  impl_->poses_in.clear();
  return out;
}

std::optional<std::array<double, 3>> SandtrayGraph::take_look_at() {
  std::lock_guard lock(impl_->mutex);
  return std::exchange(impl_->look_at, std::nullopt);
}

std::optional<std::array<double, 2>> SandtrayGraph::take_point_at() {
  std::lock_guard lock(impl_->mutex);
  return std::exchange(impl_->point_at, std::nullopt);
}

std::vector<std::string> SandtrayGraph::take_signals() {
  std::lock_guard lock(impl_->mutex);
  std::vector<std::string> out(impl_->signals_in.begin(), impl_->signals_in.end());
  impl_->signals_in.clear();
  return out;
}

std::optional<MoveGoal> SandtrayGraph::take_goal() {
  std::lock_guard lock(impl_->mutex);
  auto goal = std::move(impl_->pending_goal);
  impl_->pending_goal.reset();
  return goal;
}

bool SandtrayGraph::cancel_requested(std::uint64_t id) const {
  std::lock_guard lock(impl_->mutex);
  return impl_->cancels.count(id) != 0;
}

void SandtrayGraph::goal_feedback(std::uint64_t id, int percentage) {
  std::lock_guard lock(impl_->mutex);
  const auto it = impl_->goals.find(id);
  if (it == impl_->goals.end()) return;
  freeplay_sandbox_msgs::PlaygroundNavigationFeedback feedback;
  feedback.percentage = percentage;
  it->second.publishFeedback(feedback);
}

void SandtrayGraph::goal_done(std::uint64_t id, GoalEnd end, const std::string& status_text) {
  std::lock_guard lock(impl_->mutex);
  const auto it = impl_->goals.find(id);
  if (it == impl_->goals.end()) return;
  switch (end) {
    case GoalEnd::Succeeded: it->second.setSucceeded({}, status_text); break;
    case GoalEnd::Aborted: it->second.setAborted({}, status_text); break;
    case GoalEnd::Preempted: it->second.setCanceled({}, status_text); break;
  }
  impl_->goals.erase(it);
  impl_->cancels.erase(id);
}

std::vector<PlanRequest> SandtrayGraph::take_plan_requests() {
  std::lock_guard lock(impl_->mutex);
  std::vector<PlanRequest> out(impl_->plan_requests.begin(), impl_->plan_requests.end());
  impl_->plan_requests.clear();
  return out;
}

void SandtrayGraph::answer_plan(std::uint64_t id, const std::vector<std::array<double, 2>>& path) {
  {
    std::lock_guard lock(impl_->mutex);
    const auto it = impl_->plan_answers.find(id);
    if (it == impl_->plan_answers.end()) return;  // the caller gave up waiting
    it->second = path;
  }
  impl_->answered.notify_all();
}

}  // namespace freeplay::ros_graph
