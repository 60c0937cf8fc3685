#pragma once
// The Foxglove WebSocket protocol side of the web server (`foxglove.websocket.v1`, ROS 1 encoding): the channels a
// live session advertises, with their ros1msg schemas, and the serialised messages of a tick (recording::TickTopics,
// the bag's and the live graph's messages), so that Foxglove
// Studio connected to ws://ADDR:PORT shows the game's TF, zones, footprints and background image, the Nao's links and
// joints, and the stage cameras.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace freeplay::runner {
struct EpisodeSnapshot;
}
namespace freeplay::recording {
class TickTopics;
}

namespace freeplay::web {

/// One advertised channel.
struct FoxgloveChannel {
  int id = 0;               ///< channel id
  std::string topic;        ///< ROS topic name
  std::string schema_name;  ///< ROS message type, e.g. "tf2_msgs/TFMessage"
  std::string schema;       ///< the full ROS 1 message definition (ros1msg)
};

/// The channel ids (the stage cameras follow from kFoxgloveFirstCamera, in the scenario's order).
enum FoxgloveChannelId : int {
  kFoxgloveTf = 1,
  kFoxgloveZones = 2,
  kFoxgloveFootprints = 3,
  kFoxgloveBackground = 4,
  kFoxgloveJointStates = 5,
  kFoxgloveFirstCamera = 10
};

/// The channels of the game (/tf, /zones, /footprints, the background).
const std::vector<FoxgloveChannel>& foxglove_channels();
/// The channels a session advertises: the game's, `/joint_states` with a robot, and each stage camera's colour
/// stream (`cameras`: scenario camera names) under its driver's CompressedImage topic.
std::vector<FoxgloveChannel> foxglove_channels(const std::vector<std::string>& cameras, bool robot);

/// One serialised message for a channel.
struct FoxgloveMessage {
  int channel = 0;                               ///< channel id
  std::uint64_t stamp_ns = 0;                    ///< receive timestamp (ns, ROS time)
  std::shared_ptr<const std::string> payload;    ///< the ROS 1 serialised message
  bool latched = false;                          ///< a latched topic (a new subscriber gets the latest at once)
};

/// The channel of `topic` among the game's and the Nao's (0: none).
int foxglove_channel(const std::string& topic);

/// The game's and the Nao's messages of each tick on their channels: recording::TickTopics with kFoxgloveStreams.
class FoxgloveTopics {
 public:
  /// The topics of the episode with root `seed`; sandtray time 0 is ROS time `origin_ns`; `arm_reach_m` places the Nao.
  FoxgloveTopics(std::uint64_t seed, std::uint64_t origin_ns, double arm_reach_m);
  ~FoxgloveTopics();
  FoxgloveTopics(const FoxgloveTopics&) = delete;
  FoxgloveTopics& operator=(const FoxgloveTopics&) = delete;
  /// The tick's messages, in the order they go out (stamp_ns: when each is sent).
  std::vector<FoxgloveMessage> tick(const runner::EpisodeSnapshot& snapshot);

 private:
  std::uint64_t origin_ns_;
  std::unique_ptr<recording::TickTopics> topics_;  // (a pointer: the web server's C++17 unit includes this header)
};

/// A stage camera's colour frame (JPEG) on channel `channel` in the optical frame `frame_id`.
FoxgloveMessage foxglove_camera(int channel, const std::string& frame_id, const std::vector<std::uint8_t>& jpeg,
                                std::uint64_t stamp_ns);

/// The binary frame of one message for subscription `subscription` (opcode 0x01, little-endian ids and stamp).
std::string foxglove_frame(std::uint32_t subscription, const FoxgloveMessage& message);

}  // namespace freeplay::web
