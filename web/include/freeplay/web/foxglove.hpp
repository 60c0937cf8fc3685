#pragma once
// The Foxglove WebSocket protocol side of the web server (`foxglove.websocket.v1`, ROS 1 encoding): the channels a
// live session advertises, with their ros1msg schemas, and the serialised messages of a tick, so that Foxglove
// Studio connected to ws://ADDR:PORT shows the game's TF, zones, footprints and background image, the Nao's links and
// joints, and the stage cameras.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace freeplay::sim {
class Sandtray;
}
namespace freeplay::runner {
struct RobotSnapshot;
}
namespace freeplay::recording {
struct LinkTransform;
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
};

/// `/tf`: sandtray → every item (x, y, yaw) and every active touch (`touchN`), stamped `stamp_ns`.
FoxgloveMessage foxglove_tf(const sim::Sandtray& tray, std::uint64_t stamp_ns);
/// `/zones`: the colour zones as LINE_STRIP markers in `sandtray` (as the real zones node).
FoxgloveMessage foxglove_zones(const sim::Sandtray& tray, std::uint64_t stamp_ns);
/// `/footprints`: each item's polygon as a LINE_STRIP marker in the item's frame (as map_and_plan).
FoxgloveMessage foxglove_footprints(const sim::Sandtray& tray, std::uint64_t stamp_ns);
/// `/sandtray/background/image/compressed`: the background as a JPEG CompressedImage in `sandtray`.
FoxgloveMessage foxglove_background(const std::string& jpeg, std::uint64_t stamp_ns);

/// `/tf`: the Nao's links (robot_state_publisher's tree from the joint states), stamped `stamp_ns`.
FoxgloveMessage foxglove_robot_tf(const std::vector<recording::LinkTransform>& links, std::uint64_t stamp_ns);
/// `/joint_states`: the Nao's joints.
FoxgloveMessage foxglove_joint_states(const runner::RobotSnapshot& robot, std::uint64_t stamp_ns);
/// A stage camera's colour frame (JPEG) on channel `channel` in the optical frame `frame_id`.
FoxgloveMessage foxglove_camera(int channel, const std::string& frame_id, const std::vector<std::uint8_t>& jpeg,
                                std::uint64_t stamp_ns);

/// The binary frame of one message for subscription `subscription` (opcode 0x01, little-endian ids and stamp).
std::string foxglove_frame(std::uint32_t subscription, const FoxgloveMessage& message);

}  // namespace freeplay::web
