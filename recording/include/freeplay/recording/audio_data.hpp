#pragma once
// audio_common_msgs/AudioData (`uint8[] data`), which Debian does not package: defined here with the ROS 1 message
// traits and serializer, so rosbag writes it under its real name, MD5 and definition.

#include <cstdint>
#include <vector>

#include <ros/message_traits.h>
#include <ros/serialization.h>

#include "freeplay/recording/ros_messages.hpp"

namespace freeplay::recording::msg {

/// audio_common_msgs/AudioData: one chunk of encoded audio (MP3 frames, as audio_capture publishes them).
struct AudioData {
  std::vector<std::uint8_t, RosAllocator<std::uint8_t>> data;  ///< the encoded bytes
};

}  // namespace freeplay::recording::msg

namespace ros::message_traits {

/// The real type's MD5 (audio_common_msgs/AudioData).
template <>
struct MD5Sum<freeplay::recording::msg::AudioData> {
  /// The MD5 sum.
  static const char* value() { return "f43a8e1b362b75baa741461b46adc7e0"; }
  /// The MD5 sum.
  static const char* value(const freeplay::recording::msg::AudioData&) { return value(); }
  static const std::uint64_t static_value1 = 0xf43a8e1b362b75baULL;  ///< first half
  static const std::uint64_t static_value2 = 0xa741461b46adc7e0ULL;  ///< second half
};

/// The real type's name.
template <>
struct DataType<freeplay::recording::msg::AudioData> {
  /// The type name.
  static const char* value() { return "audio_common_msgs/AudioData"; }
  /// The type name.
  static const char* value(const freeplay::recording::msg::AudioData&) { return value(); }
};

/// The real type's definition.
template <>
struct Definition<freeplay::recording::msg::AudioData> {
  /// The message definition.
  static const char* value() { return "uint8[] data\n"; }
  /// The message definition.
  static const char* value(const freeplay::recording::msg::AudioData&) { return value(); }
};

}  // namespace ros::message_traits

namespace ros::serialization {

/// Serializes AudioData as ROS 1 does a `uint8[]` (length, bytes).
template <>
struct Serializer<freeplay::recording::msg::AudioData> {
  /// Reads, writes or measures the message.
  template <typename Stream, typename T>
  inline static void allInOne(Stream& stream, T m) {
    stream.next(m.data);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};

}  // namespace ros::serialization
