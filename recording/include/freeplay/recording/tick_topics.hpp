#pragma once
// What the game and its core nodes send out each tick, declared once: which topic, which message, which stamp and
// when (free-play-sandbox.md §2.2, §2.4). The bag recorder, the live ROS graph (`freeplay serve`) and the Foxglove
// channels of the web page all take their tick topics from TickTopics; each carries a declared set of its streams
// (kBagStreams, kLiveGraphStreams, kFoxgloveStreams) and maps the stamps onto its own time base (docs/recording.md).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/recording/session_layout.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/runner/robot_body.hpp"

namespace freeplay::recording {

/// The streams of the tick, one per real publisher group; a front carries a set of them (bit flags).
enum TickStream : unsigned {
  kGameFrames = 1U << 0,      ///< /tf: every item and every active touch, one message per TFBroadcaster (game)
  kCameraLinkFrames = 1U << 1,    ///< /tf: sandtray_publisher's URDF camera links, one message
  kHeadTrackers = 1U << 2,    ///< /tf: gazr's `child_<seat>_0` per child (x axis along the gaze)
  kRobotFocus = 1U << 3,      ///< /tf: `robot_focus`, the robot's gaze point
  kRobotLinks = 1U << 4,      ///< /tf: robot_state_publisher's Nao links (child-robot)
  kArmReach = 1U << 5,        ///< /tf: `arm_reach` (sandtray_localisation's broadcast_arm_reach), once set
  kJointStates = 1U << 6,     ///< /joint_states (child-robot)
  kFingerPoses = 1U << 7,     ///< /poses: the robot's virtual finger (move_sandbox_items)
  kTrajectory = 1U << 8,      ///< /visualization_markers: the move's trajectory so far (move_sandbox_items)
  kFootprints = 1U << 9,      ///< /footprints: once, 1 s after start, latched (FootprintsPublisher)
  kBackground = 1U << 10,     ///< /sandtray/background/image/compressed: PNG on every new background, latched
  kBackgroundRaw = 1U << 11,  ///< /sandtray/background/image (rgba8) and camera_info with it, latched
  kZones = 1U << 12,          ///< /zones with every new background, latched (zones_from_image)
  kMap = 1U << 13,            ///< /map at 5 Hz (map_and_plan)
  kEventTopics = 1U << 14,    ///< per event: interaction events, the robot's speech, the protocol stages' signals
};

/// What the bag records (record.launch's topics plus the robot's, docs/recording.md).
inline constexpr unsigned kBagStreams = kGameFrames | kCameraLinkFrames | kHeadTrackers | kRobotFocus | kRobotLinks |
                                        kJointStates | kFingerPoses | kFootprints | kBackground | kZones | kEventTopics;
/// What `freeplay serve` publishes as the game and core nodes (the robot's own nodes publish the rest).
inline constexpr unsigned kLiveGraphStreams = kGameFrames | kCameraLinkFrames | kArmReach | kJointStates | kFingerPoses |
                                              kTrajectory | kFootprints | kBackground | kBackgroundRaw | kZones | kMap |
                                              kEventTopics;
/// What the web page's Foxglove channels carry.
inline constexpr unsigned kFoxgloveStreams =
    kGameFrames | kRobotLinks | kJointStates | kFootprints | kBackground | kZones;

/// A message of any type the tick sends.
using TopicPayload = std::variant<msg::TFMessage, msg::MarkerArray, msg::Marker, msg::CompressedImage, msg::Image,
                                  msg::CameraInfo, msg::OccupancyGrid, msg::JointState, msg::PoseStamped, msg::String,
                                  msg::Empty>;

/// One message of the tick.
struct TopicMessage {
  std::string topic;        ///< e.g. "/tf"
  std::string publisher;    ///< the real publisher whose clock stamped it, e.g. "game/hippo"
  double published = 0.0;   ///< sandtray time it is sent (s); its header stamps are the time base's origin + this
  bool latched = false;     ///< a latched topic
  TopicPayload message;     ///< the message
};

/// A topic the tick sends, as an advertisement (or a Foxglove channel) declares it.
struct TopicDeclaration {
  std::string topic;        ///< e.g. "/tf"
  std::string datatype;     ///< e.g. "tf2_msgs/TFMessage"
  std::string md5sum;       ///< the type's MD5 sum
  std::string definition;   ///< the full message definition
  bool latched = false;     ///< a latched topic
};

/// The topics `streams` (TickStream flags) send, each once: /tf, /zones, /footprints, the background (compressed,
/// raw, camera_info), /joint_states, /poses, /visualization_markers, /map, then the event topics.
std::vector<TopicDeclaration> declared_topics(unsigned streams);

/// One message in the ROS 1 wire format, with what a connection header needs.
struct SerializedTopicMessage {
  TopicDeclaration declaration;  ///< its topic, type and latching
  std::uint64_t stamp_ns = 0;    ///< when it is sent (ns, the front's ROS time)
  std::shared_ptr<const std::vector<std::uint8_t>> bytes;  ///< the serialised message
};

/// Settings of a TickTopics.
struct TickTopicsOptions {
  unsigned streams = kBagStreams;   ///< the streams to make (TickStream flags)
  std::uint64_t origin_ns = static_cast<std::uint64_t>(kEpochS) * 1000000000ULL;  ///< ROS time of sandtray time 0
  int png_level = 3;                ///< PNG level of the background (the real launch file's)
  double arm_reach_m = 0.5;         ///< the scenario's arm reach (places the Nao for its link frames)
};

/// The tick topics of one episode: every message the game and its core nodes send for a snapshot, stamped by each
/// publisher's own clock (PublisherClock, seeded by the episode). The bag writes frames(), its audio, then state();
/// the live fronts send tick().
class TickTopics {
 public:
  /// The topics of the episode with root `seed`.
  TickTopics(std::uint64_t seed, TickTopicsOptions options);
  ~TickTopics();
  TickTopics(const TickTopics&) = delete;
  TickTopics& operator=(const TickTopics&) = delete;
  /// Moves the topics (and their clocks) over.
  TickTopics(TickTopics&& other) noexcept;
  /// Moves the topics (and their clocks) over.
  TickTopics& operator=(TickTopics&& other) noexcept;

  /// The tick's TF broadcasters (items, touches, camera links, head trackers, robot focus), sent first.
  std::vector<TopicMessage> frames(const runner::EpisodeSnapshot& snapshot);
  /// The rest of the tick, after the frames: background, zones, footprints, the robot's joints, links and finger,
  /// the map and `arm_reach`.
  std::vector<TopicMessage> state(const runner::EpisodeSnapshot& snapshot);
  /// The whole tick (frames() and state()) in the order the publishers send it: by publication time, as a
  /// subscriber (or `rosbag play`) sees it.
  std::vector<TopicMessage> tick(const runner::EpisodeSnapshot& snapshot);
  /// The real topics event `e` of the tick `t` goes out on (kEventTopics), at the tick's time: `releasing_<item>` on
  /// /sandtray/interaction_events, the robot's `say` on /speech, the start of the tutorial, free play and debriefing
  /// on /sandtray/signals/{start_tutorial,start_freeplay,blank_interface} (as the supervisor sends them).
  std::vector<TopicMessage> event(double t, const Event& e) const;
  /// Sets (or, with nullopt, stops) the `arm_reach` frame of kArmReach.
  void set_arm_reach(const std::optional<runner::ReachDisc>& reach);
  /// The ROS time (ns) of sandtray time `t`.
  std::uint64_t stamp_ns(double t) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `message` in the ROS 1 wire format, stamped on the time base whose origin is `origin_ns`.
SerializedTopicMessage serialize(const TopicMessage& message, std::uint64_t origin_ns);

}  // namespace freeplay::recording
