#include <gtest/gtest.h>
#include <ros/serialization.h>

#include <map>

#include "freeplay/core/rng.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/recording/robot_links.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/web/foxglove.hpp"

using namespace freeplay;
using namespace freeplay::web;

namespace {

template <typename Message>
Message decode(const FoxgloveMessage& m) {
  Message out;
  std::string bytes = *m.payload;
  ros::serialization::IStream in(reinterpret_cast<std::uint8_t*>(bytes.data()), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(in, out);
  return out;
}

runner::EpisodeSnapshot snapshot_of(const sim::Sandtray& tray, double t, const runner::RobotSnapshot* robot = nullptr) {
  runner::EpisodeSnapshot s;
  s.t = t;
  s.stage = "freeplay";
  s.tray = &tray;
  s.robot = robot;
  return s;
}

}  // namespace

TEST(WebFoxglove, TfMessagesAreRos1SerialisedInTheSandtrayFrame) {
  sim::Sandtray tray(runner::SharedModels::shipped().catalogue, {}, Rng(1));
  tray.signal(sim::Signal::StartFreeplay);
  tray.step(1.0);
  const std::uint64_t origin_ns = 1500000000123456789ULL;
  FoxgloveTopics topics(1, origin_ns, 0.5);
  std::vector<FoxgloveMessage> tf_messages;
  for (auto& m : topics.tick(snapshot_of(tray, 1.0))) {
    if (m.channel == kFoxgloveTf) tf_messages.push_back(std::move(m));
  }
  ASSERT_EQ(tf_messages.size(), 10u);  // one per item's TF broadcaster, as the game and the bag
  const auto zebra = tray.item("zebra").pose;
  bool found = false;
  for (const auto& m : tf_messages) {
    const auto tf = decode<recording::msg::TFMessage>(m);
    ASSERT_EQ(tf.transforms.size(), 1u);
    const auto& t = tf.transforms[0];
    EXPECT_EQ(recording::std_string(t.header.frame_id), "sandtray");
    EXPECT_EQ(t.header.stamp.toNSec(), m.stamp_ns);  // each broadcaster's own phase after the tick
    EXPECT_GT(m.stamp_ns, origin_ns + 1000000000ULL);
    EXPECT_LT(m.stamp_ns, origin_ns + 1050000000ULL);
    if (recording::std_string(t.child_frame_id) != "zebra") continue;
    found = true;
    EXPECT_DOUBLE_EQ(t.transform.translation.x, zebra.x);
    EXPECT_DOUBLE_EQ(t.transform.translation.y, zebra.y);
    EXPECT_NEAR(2.0 * std::atan2(t.transform.rotation.z, t.transform.rotation.w), zebra.theta, 1e-9);
  }
  EXPECT_TRUE(found);
}

TEST(WebFoxglove, ZonesFootprintsAndTheBackgroundAreTheRealTopicsAndLatched) {
  sim::Sandtray tray(runner::SharedModels::shipped().catalogue, {}, Rng(1));
  tray.signal(sim::Signal::StartFreeplay);
  FoxgloveTopics topics(1, 0, 0.5);
  std::map<int, std::vector<FoxgloveMessage>> by_channel;
  for (int k = 0; k <= 10; ++k) {
    for (auto& m : topics.tick(snapshot_of(tray, 0.1 * k))) by_channel[m.channel].push_back(std::move(m));
  }
  ASSERT_EQ(by_channel[kFoxgloveBackground].size(), 1u);
  EXPECT_TRUE(by_channel[kFoxgloveBackground][0].latched);
  EXPECT_EQ(recording::std_string(decode<recording::msg::CompressedImage>(by_channel[kFoxgloveBackground][0]).format),
            "rgba8; png compressed bgr8");
  ASSERT_EQ(by_channel[kFoxgloveZones].size(), 1u);
  EXPECT_EQ(decode<recording::msg::MarkerArray>(by_channel[kFoxgloveZones][0]).markers[0].action,
            recording::msg::Marker::DELETEALL);
  ASSERT_EQ(by_channel[kFoxgloveFootprints].size(), 1u);  // once, 1 s after the start
  EXPECT_GE(by_channel[kFoxgloveFootprints][0].stamp_ns, 1000000000u);
  EXPECT_EQ(recording::std_string(decode<recording::msg::MarkerArray>(by_channel[kFoxgloveFootprints][0]).markers[0].ns),
            recording::std_string(decode<recording::msg::MarkerArray>(by_channel[kFoxgloveFootprints][0]).markers[0].header.frame_id).substr(1));
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

TEST(WebFoxglove, ASessionWithARobotAndCamerasAdvertisesTheirChannels) {
  const auto channels = foxglove_channels({"env_camera", "camera_purple"}, true);
  std::map<std::string, std::pair<int, std::string>> by_topic;
  for (const auto& c : channels) by_topic[c.topic] = {c.id, c.schema_name};
  EXPECT_EQ(by_topic["/joint_states"], (std::pair<int, std::string>{kFoxgloveJointStates, "sensor_msgs/JointState"}));
  EXPECT_EQ(by_topic["/env_camera/qhd/image_color/compressed"],
            (std::pair<int, std::string>{kFoxgloveFirstCamera, "sensor_msgs/CompressedImage"}));
  EXPECT_EQ(by_topic["/camera_purple/rgb/image_raw/compressed"].first, kFoxgloveFirstCamera + 1);
  EXPECT_EQ(foxglove_channels({}, false).size(), 4u);  // child-child without cameras: the game's only
}

TEST(WebFoxglove, TheNaosJointsAndLinksAndACameraFrameAreRos1Messages) {
  // The Nao as an episode's first tick shows it.
  const auto s = scenario::scenario_from_document(parse_yaml(
      "name: t\ncondition: child-robot\nprotocol: {greeting_s: 0.2, tutorial_s: 0.1, freeplay_cap_s: 1, debriefing_s: 0.1}\n",
      "test.yaml"));
  struct First final : runner::EpisodeObserver {
    runner::RobotSnapshot robot;
    void observe(const runner::EpisodeSnapshot& snapshot) override {
      if (robot.joint_names.empty() && snapshot.robot != nullptr) robot = *snapshot.robot;
    }
  };
  auto first = std::make_unique<First>();
  auto* keep = first.get();
  runner::EpisodeObservers observers;
  observers.push_back(std::move(first));
  const std::atomic<bool> stop{false};
  runner::run_episode({.scenario = s, .seed = 1, .stop = stop, .id = "nao"}, runner::observed_by(observers));
  const auto& robot = keep->robot;
  ASSERT_GT(robot.joint_names.size(), 20u);

  sim::Sandtray tray(runner::SharedModels::shipped().catalogue, {}, Rng(1));
  FoxgloveTopics topics(1, 0, s.robot.arm_reach_m);
  std::vector<FoxgloveMessage> joint_states, robot_tf;
  for (auto& m : topics.tick(snapshot_of(tray, 0.0, &robot))) {
    if (m.channel == kFoxgloveJointStates) joint_states.push_back(m);
    if (m.channel == kFoxgloveTf && decode<recording::msg::TFMessage>(m).transforms.size() > 1) robot_tf.push_back(m);
  }
  ASSERT_EQ(joint_states.size(), 1u);
  const auto joints = decode<recording::msg::JointState>(joint_states[0]);
  ASSERT_EQ(joints.name.size(), robot.joint_names.size());
  EXPECT_EQ(recording::std_string(joints.name[0]), robot.joint_names[0]);
  EXPECT_DOUBLE_EQ(joints.position[3], robot.positions[3]);

  recording::NaoLinkFrames frames(s.robot.arm_reach_m);
  const auto& links = frames.compute(robot.joint_names, robot.positions);
  ASSERT_EQ(robot_tf.size(), 1u);  // robot_state_publisher's tree, one message beside the game's
  const auto tf = decode<recording::msg::TFMessage>(robot_tf[0]);
  ASSERT_EQ(tf.transforms.size(), links.size());
  EXPECT_EQ(recording::std_string(tf.transforms[0].header.frame_id), "sandtray");
  EXPECT_EQ(recording::std_string(tf.transforms[0].child_frame_id), "base_link");
  EXPECT_DOUBLE_EQ(tf.transforms[0].transform.translation.x, links[0].parent_T_child.translation().x());

  const auto image = decode<recording::msg::CompressedImage>(
      foxglove_camera(kFoxgloveFirstCamera, "env_camera_rgb_optical_frame", {0xff, 0xd8, 0xff}, 42));
  EXPECT_EQ(recording::std_string(image.format), "jpeg");
  EXPECT_EQ(recording::std_string(image.header.frame_id), "env_camera_rgb_optical_frame");
  EXPECT_EQ(image.data.size(), 3u);
}
