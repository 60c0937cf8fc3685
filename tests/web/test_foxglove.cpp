#include <gtest/gtest.h>
#include <ros/serialization.h>

#include "freeplay/core/rng.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/web/foxglove.hpp"

using namespace freeplay;
using namespace freeplay::web;

TEST(WebFoxglove, TfMessagesAreRos1SerialisedInTheSandtrayFrame) {
  sim::Sandtray tray(runner::SharedModels::shipped().catalogue, {}, Rng(1));
  tray.signal(sim::Signal::StartFreeplay);
  tray.step(1.0);
  const auto m = foxglove_tf(tray, 1500000000123456789ULL);
  EXPECT_EQ(m.channel, kFoxgloveTf);
  recording::msg::TFMessage tf;
  std::string bytes = *m.payload;
  ros::serialization::IStream in(reinterpret_cast<std::uint8_t*>(bytes.data()), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(in, tf);
  ASSERT_EQ(tf.transforms.size(), 10u);
  const auto zebra = tray.item("zebra").pose;
  bool found = false;
  for (const auto& t : tf.transforms) {
    EXPECT_EQ(recording::std_string(t.header.frame_id), "sandtray");
    EXPECT_EQ(t.header.stamp.toNSec(), 1500000000123456789ULL);
    if (recording::std_string(t.child_frame_id) != "zebra") continue;
    found = true;
    EXPECT_DOUBLE_EQ(t.transform.translation.x, zebra.x);
    EXPECT_DOUBLE_EQ(t.transform.translation.y, zebra.y);
    EXPECT_NEAR(2.0 * std::atan2(t.transform.rotation.z, t.transform.rotation.w), zebra.theta, 1e-9);
  }
  EXPECT_TRUE(found);
}

TEST(WebFoxglove, BinaryFramesCarryTheSubscriptionAndStampLittleEndian) {
  const FoxgloveMessage m{kFoxgloveTf, 0x0102030405060708ULL, std::make_shared<const std::string>("abc")};
  const auto frame = foxglove_frame(0x0A0B0C0DU, m);
  ASSERT_EQ(frame.size(), 1u + 4u + 8u + 3u);
  EXPECT_EQ(frame[0], 0x01);
  EXPECT_EQ(frame.substr(1, 4), std::string("\x0D\x0C\x0B\x0A", 4));
  EXPECT_EQ(frame.substr(5, 8), std::string("\x08\x07\x06\x05\x04\x03\x02\x01", 8));
  EXPECT_EQ(frame.substr(13), "abc");
  const auto& channels = foxglove_channels();
  ASSERT_EQ(channels.size(), 4u);
  EXPECT_EQ(channels[0].schema_name, "tf2_msgs/TFMessage");
  EXPECT_NE(channels[0].schema.find("MSG: geometry_msgs/TransformStamped"), std::string::npos);
}
