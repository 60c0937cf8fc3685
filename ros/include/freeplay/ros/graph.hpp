#pragma once
// The live ROS 1 graph as plain data: what `freeplay serve` publishes and receives as the sandtray game and core
// nodes, and what `freeplay robot` reads and sends as the robot's nodes. The ROS side is compiled as C++17 (Debian's
// message headers need std::allocator::rebind, which C++20 removed), so this header holds only standard types.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace freeplay::ros_graph {

/// One TF transform (translation in m, rotation as a unit quaternion x, y, z, w).
struct Transform {
  std::string parent;                       ///< e.g. "sandtray"
  std::string child;                        ///< e.g. "hippo"
  std::array<double, 3> translation{};      ///< x, y, z
  std::array<double, 4> rotation{0, 0, 0, 1};  ///< qx, qy, qz, qw
  double received = 0.0;                    ///< wall time it arrived (received frames only)
};

/// A closed polygon marker (visualization_msgs/Marker LINE_STRIP) as `/footprints` and `/zones` carry them.
struct Polyline {
  std::string frame;                              ///< header.frame_id ("/hippo", "/sandtray")
  std::string ns;                                 ///< marker namespace ("hippo", "sandbox_zone_blue")
  int id = 0;                                     ///< marker id
  std::vector<std::array<double, 2>> points;      ///< x, y (m), first point repeated at the end
  std::array<float, 3> rgb{0.F, 1.F, 0.F};        ///< colour
  double width = 0.002;                           ///< scale.x (m)
};

/// One camera frame as its driver publishes it: a JPEG sensor_msgs/CompressedImage and its CameraInfo.
struct CameraFrame {
  std::string image_topic;         ///< e.g. "/naoqi_driver/camera/front/image_raw/compressed"
  std::string info_topic;          ///< e.g. "/naoqi_driver/camera/front/camera_info"
  std::string frame_id;            ///< optical frame
  std::string format;              ///< CompressedImage.format, e.g. "rgb8; jpeg compressed bgr8"
  std::vector<std::uint8_t> jpeg;  ///< the image
  int width = 0;                   ///< px
  int height = 0;                  ///< px
  std::array<double, 4> K{};       ///< fx, fy, cx, cy (px)
};

/// A `/poses` message received (a robot finger pose).
struct FingerPose {
  double x = 0.0;            ///< m
  double y = 0.0;            ///< m
  std::string frame;         ///< header.frame_id
  std::string publisher;     ///< caller id of the sender
};

/// A `move_sandbox_items` goal (freeplay_sandbox_msgs/PlaygroundNavigationGoal) received.
struct MoveGoal {
  std::uint64_t id = 0;      ///< our handle for the goal
  std::string item;          ///< item (TF frame) name
  double x = 0.0;            ///< goal point in `sandtray` (m)
  double y = 0.0;            ///< goal point in `sandtray` (m)
  double z = 0.0;            ///< ignored by the game
};

/// How a goal ended.
enum class GoalEnd { Succeeded, Aborted, Preempted };

/// A `plan_motion` request (freeplay_sandbox_msgs/PlaygroundPlan) received.
struct PlanRequest {
  std::uint64_t id = 0;      ///< our handle for the request
  std::string frame;         ///< goal.header.frame_id: the item to move
  double x = 0.0;            ///< goal position (in `frame`, m)
  double y = 0.0;            ///< goal position (in `frame`, m)
};

/// A message already in the ROS 1 wire format, with what its advertisement needs (recording::TickTopics makes them).
struct SerializedMessage {
  std::string topic;        ///< e.g. "/tf"
  std::string datatype;     ///< e.g. "tf2_msgs/TFMessage"
  std::string md5sum;       ///< the type's MD5 sum
  std::string definition;   ///< the full message definition
  bool latched = false;     ///< advertised latched (and published again after a master restart)
  std::shared_ptr<const std::vector<std::uint8_t>> bytes;  ///< the serialised message
};

/// Options of a node.
struct NodeOptions {
  std::string name;              ///< ros::init node name ("sandtray", "freeplay_robot")
  bool publish_clock = false;    ///< serve: publish `/clock` (for use_sim_time)
  bool core_servers = false;     ///< serve: offer `move_sandbox_items` and `plan_motion`
};

/// Starts the ROS client of this process (ros::init) once; false with `error` set when the master is unreachable
/// within `timeout_s`.
bool start_ros(const std::string& node_name, double timeout_s, std::string& error);

/// The sandtray game and core nodes on the graph (`freeplay serve`).
class SandtrayGraph {
 public:
  /// Advertises every topic and server; call start_ros first.
  explicit SandtrayGraph(const NodeOptions& options);
  ~SandtrayGraph();
  SandtrayGraph(const SandtrayGraph&) = delete;
  SandtrayGraph& operator=(const SandtrayGraph&) = delete;

  /// False once ROS shut down (master gone for good, Ctrl-C through ROS).
  bool ok() const;
  /// Call once per tick: after the master came back from a restart, registers every topic and server anew and
  /// publishes the latched topics again (goals accepted before are aborted).
  void maintain();
  /// Publishes `/clock` (only with publish_clock).
  void clock(double stamp);
  /// Advertises the topic of `declaration` (its bytes are not used) now and after every master restart.
  void advertise(const SerializedMessage& declaration);
  /// Publishes one message as it is (a topic not advertised yet is advertised at its first message).
  void publish(const SerializedMessage& message);
  /// Publishes one `/tf` message with `transforms`.
  void tf(double stamp, const std::vector<Transform>& transforms);
  /// Publishes `speech` (std_msgs/String: the Nao's text to speech).
  void speech(const std::string& text);
  /// Publishes one `/poses` message (frame `/sandtray`) from our own move executor.
  void finger(double stamp, double x, double y);
  /// Publishes one camera frame (its topics are advertised at the first frame).
  void camera(double stamp, const CameraFrame& frame);

  /// `/poses` received from other nodes since the last call (malformed ones are logged and dropped).
  std::vector<FingerPose> take_poses();
  /// The latest gaze target on `freeplay/robot/look_at` since the last call (x, y, z in `sandtray`).
  std::optional<std::array<double, 3>> take_look_at();
  /// The latest pointing target on `freeplay/robot/point_at` since the last call (x, y in `sandtray`).
  std::optional<std::array<double, 2>> take_point_at();
  /// `sandtray/signals/*` received from other nodes since the last call (names without the prefix).
  std::vector<std::string> take_signals();
  /// The newest `move_sandbox_items` goal received since the last call (older unclaimed ones are preempted).
  std::optional<MoveGoal> take_goal();
  /// True when the client asked to cancel goal `id`.
  bool cancel_requested(std::uint64_t id) const;
  /// Publishes feedback `percentage` for goal `id`.
  void goal_feedback(std::uint64_t id, int percentage);
  /// Ends goal `id` with `status_text` (e.g. the reason of an abort).
  void goal_done(std::uint64_t id, GoalEnd end, const std::string& status_text);
  /// `plan_motion` requests waiting for an answer.
  std::vector<PlanRequest> take_plan_requests();
  /// Answers request `id` with `path` in `/sandtray` (empty = no path).
  void answer_plan(std::uint64_t id, const std::vector<std::array<double, 2>>& path);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What the robot's nodes know of the sandtray from the graph (`freeplay robot`).
struct RobotView {
  std::vector<Transform> frames;               ///< latest transform of every child frame of `sandtray`
  std::vector<Polyline> zones;                 ///< latest `/zones` (DELETEALL dropped)
  std::vector<Polyline> footprints;            ///< latest `/footprints`
  std::vector<std::string> interaction_events; ///< `sandtray/interaction_events` since the last call
  std::array<int, 2> faces{-1, -1};            ///< `/camera_purple/nb_detected_faces`, `/camera_yellow/…` (−1: none yet)
  bool freeplay_started = false;               ///< `sandtray/signals/start_freeplay` seen
};

/// The robot's nodes on the graph: reads TF, zones, footprints and events; sends `/poses`, speech, gaze, pointing.
class RobotGraph {
 public:
  /// Subscribes and advertises; call start_ros first.
  RobotGraph();
  ~RobotGraph();
  RobotGraph(const RobotGraph&) = delete;
  RobotGraph& operator=(const RobotGraph&) = delete;

  /// False once ROS shut down.
  bool ok() const;
  /// Call once per tick: after the master came back from a restart, subscribes and advertises anew.
  void maintain();
  /// A copy of what is known now (events are handed out once).
  RobotView take();
  /// Publishes one `/poses` fake touch (frame `/sandtray`).
  void finger(double x, double y);
  /// Publishes `speech`.
  void speech(const std::string& text);
  /// Publishes a gaze target on `freeplay/robot/look_at` (geometry_msgs/PointStamped, frame `sandtray`).
  void look_at(double x, double y, double z);
  /// Publishes a pointing target on `freeplay/robot/point_at` (geometry_msgs/PointStamped, frame `sandtray`).
  void point_at(double x, double y);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Wall-clock ROS time now (s since the epoch).
double wall_now();

}  // namespace freeplay::ros_graph
