#include "freeplay/web/foxglove.hpp"

#include <fmt/format.h>

#include <map>
#include <ros/serialization.h>

#include "freeplay/recording/camera_topics.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/recording/tick_topics.hpp"
#include "freeplay/runner/episode_observer.hpp"

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

// The channels of the game's topics (and the Nao's, with `robot`), as recording::declared_topics declares them.
std::vector<FoxgloveChannel> game_channels(bool robot) {
  const unsigned nao = recording::kRobotLinks | recording::kJointStates;
  std::vector<FoxgloveChannel> out;
  for (const auto& d : recording::declared_topics(robot ? recording::kFoxgloveStreams : recording::kFoxgloveStreams & ~nao)) {
    out.push_back({foxglove_channel(d.topic), d.topic, d.datatype, d.definition});
  }
  return out;
}

recording::TickTopicsOptions foxglove_options(std::uint64_t origin_ns, double arm_reach_m) {
  recording::TickTopicsOptions options;
  options.streams = recording::kFoxgloveStreams;
  options.origin_ns = origin_ns;
  options.arm_reach_m = arm_reach_m;
  return options;
}

}  // namespace

const std::vector<FoxgloveChannel>& foxglove_channels() {
  static const std::vector<FoxgloveChannel> kChannels = game_channels(false);
  return kChannels;
}

std::vector<FoxgloveChannel> foxglove_channels(const std::vector<std::string>& cameras, bool robot) {
  auto out = game_channels(robot);
  int id = kFoxgloveFirstCamera;
  for (const auto& name : cameras) {
    const auto topic = recording::camera_topics(name).rgb_image;
    out.push_back(channel<msg::CompressedImage>(id++, topic.starts_with('/') ? topic : fmt::format("/{}", topic)));
  }
  return out;
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

int foxglove_channel(const std::string& topic) {
  static const std::map<std::string, int> kChannels = {{recording::topics::kTf, kFoxgloveTf},
                                                       {recording::topics::kZones, kFoxgloveZones},
                                                       {recording::topics::kFootprints, kFoxgloveFootprints},
                                                       {recording::topics::kBackground, kFoxgloveBackground},
                                                       {recording::topics::kJointStates, kFoxgloveJointStates}};
  const auto it = kChannels.find(topic);
  return it == kChannels.end() ? 0 : it->second;
}

FoxgloveTopics::FoxgloveTopics(std::uint64_t seed, std::uint64_t origin_ns, double arm_reach_m)
    : origin_ns_(origin_ns), topics_(std::make_unique<recording::TickTopics>(seed, foxglove_options(origin_ns, arm_reach_m))) {}

FoxgloveTopics::~FoxgloveTopics() = default;

std::vector<FoxgloveMessage> FoxgloveTopics::tick(const runner::EpisodeSnapshot& snapshot) {
  std::vector<FoxgloveMessage> out;
  for (const auto& m : topics_->tick(snapshot)) {
    const int channel = foxglove_channel(m.topic);
    if (channel == 0) continue;
    const auto serialized = recording::serialize(m, origin_ns_);
    const auto& bytes = *serialized.bytes;
    out.push_back({channel, serialized.stamp_ns, std::make_shared<const std::string>(bytes.begin(), bytes.end()),
                   serialized.declaration.latched});
  }
  return out;
}

std::string foxglove_frame(std::uint32_t subscription, const FoxgloveMessage& message) {
  std::string frame(1 + 4 + 8, '\0');
  frame[0] = 0x01;  // message data
  for (int i = 0; i < 4; ++i) frame[static_cast<std::size_t>(1 + i)] = static_cast<char>((subscription >> (8 * i)) & 0xFF);
  for (int i = 0; i < 8; ++i) frame[static_cast<std::size_t>(5 + i)] = static_cast<char>((message.stamp_ns >> (8 * i)) & 0xFF);
  return frame + *message.payload;
}

}  // namespace freeplay::web
