// The tick's real topics, declared once (recording::TickTopics): frames at the items' centres, footprints once at
// 1 s in the items' frames, zones as zones_from_image, the background and the occupancy map as the real nodes lay
// them out, each publisher stamping with its own clock, and each front's streams only.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>

#include "freeplay/planning/occupancy_grid.hpp"
#include "freeplay/recording/tick_topics.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::recording {
namespace {

std::unique_ptr<sim::Sandtray> free_play_tray() {
  static const auto catalogue = std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default());
  sim::SandtrayConfig config;
  config.raster_width_px = 240;
  auto tray = std::make_unique<sim::Sandtray>(catalogue, config, Rng(3));
  tray->signal(sim::Signal::StartFreeplay);
  tray->place_item("hippo", Pose2{0.2, -0.1, 0.5});
  return tray;
}

runner::EpisodeSnapshot snapshot_at(double t, const sim::Sandtray& tray) {
  runner::EpisodeSnapshot s;
  s.t = t;
  s.stage = "freeplay";
  s.tray = &tray;
  return s;
}

TickTopics topics_of(unsigned streams, std::uint64_t seed = 7) {
  TickTopicsOptions options;
  options.streams = streams;
  return TickTopics(seed, options);
}

template <class M>
std::vector<M> of_topic(const std::vector<TopicMessage>& messages, const std::string& topic) {
  std::vector<M> out;
  for (const auto& m : messages) {
    if (m.topic == topic) out.push_back(std::get<M>(m.message));
  }
  return out;
}

TEST(TickTopics, ItemFramesAreAtTheCentresWithTheirYawOneMessagePerBroadcaster) {
  const auto tray = free_play_tray();
  auto topics = topics_of(kGameFrames);
  const auto frames = of_topic<msg::TFMessage>(topics.frames(snapshot_at(0.0, *tray)), topics::kTf);
  ASSERT_EQ(frames.size(), 10U);  // no finger down: one broadcaster per item
  bool hippo = false;
  for (const auto& tf : frames) {
    ASSERT_EQ(tf.transforms.size(), 1U);
    const auto& t = tf.transforms[0];
    EXPECT_EQ(std_string(t.header.frame_id), "sandtray");
    if (std_string(t.child_frame_id) != "hippo") continue;
    hippo = true;
    EXPECT_NEAR(t.transform.translation.x, 0.2, 1e-9);
    EXPECT_NEAR(t.transform.translation.y, -0.1, 1e-9);
    EXPECT_NEAR(2.0 * std::atan2(t.transform.rotation.z, t.transform.rotation.w), 0.5, 1e-9);
  }
  EXPECT_TRUE(hippo);
  tray->touch_down(2, {0.5, -0.3});
  const auto with_touch = of_topic<msg::TFMessage>(topics.frames(snapshot_at(0.1, *tray)), topics::kTf);
  ASSERT_EQ(with_touch.size(), 11U);
  EXPECT_EQ(std_string(with_touch.back().transforms[0].child_frame_id), "touch2");
}

TEST(TickTopics, EveryPublisherStampsWithItsOwnPhaseAfterTheTick) {
  const auto tray = free_play_tray();
  auto topics = topics_of(kGameFrames | kCameraLinkFrames);
  std::set<long> phases_us;
  for (const auto& m : topics.frames(snapshot_at(2.0, *tray))) {
    EXPECT_GT(m.published, 2.0);
    EXPECT_LE(m.published, 2.0 + kMaxPublishDelayS);
    EXPECT_EQ(publication_tick(m.published), 20);
    const auto& tf = std::get<msg::TFMessage>(m.message);
    EXPECT_EQ(tf.transforms[0].header.stamp, ros_time(m.published));  // the bag's time base by default
    phases_us.insert(std::lround((m.published - 2.0) * 1e6));
  }
  EXPECT_GT(phases_us.size(), 5U);  // not one phase for all
  auto again = topics_of(kGameFrames | kCameraLinkFrames);
  const auto first = topics.frames(snapshot_at(2.1, *tray));
  again.frames(snapshot_at(2.0, *tray));
  const auto replayed = again.frames(snapshot_at(2.1, *tray));
  ASSERT_EQ(first.size(), replayed.size());
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_EQ(first[i].published, replayed[i].published);  // seeded
}

TEST(TickTopics, FootprintsGoOutOnceAtOneSecondAsClosedPolygonsInTheItemsFrames) {
  const auto tray = free_play_tray();
  auto topics = topics_of(kFootprints);
  int sent = 0;
  for (int k = 0; k <= 30; ++k) {
    for (const auto& m : topics.state(snapshot_at(0.1 * k, *tray))) {
      ASSERT_EQ(m.topic, topics::kFootprints);
      EXPECT_TRUE(m.latched);
      EXPECT_EQ(publication_tick(m.published), 10);  // ~1 s after start (free-play-sandbox.md §2.2)
      const auto& markers = std::get<msg::MarkerArray>(m.message).markers;
      ASSERT_EQ(markers.size(), 10U);
      for (const auto& marker : markers) {
        const auto frame = std_string(marker.header.frame_id);  // "/<item>"
        ASSERT_FALSE(frame.empty());
        EXPECT_EQ(frame.front(), '/');
        EXPECT_EQ(frame.substr(1), std_string(marker.ns));
        ASSERT_GE(marker.points.size(), 4U);
        EXPECT_EQ(marker.points.front(), marker.points.back());
      }
      ++sent;
    }
  }
  EXPECT_EQ(sent, 1);
}

TEST(TickTopics, ZonesAndBackgroundFollowTheRealNodes) {
  const auto tray = free_play_tray();
  auto topics = topics_of(kZones | kBackground | kBackgroundRaw);
  const auto first = topics.state(snapshot_at(0.0, *tray));
  const auto zones = of_topic<msg::MarkerArray>(first, topics::kZones);
  ASSERT_EQ(zones.size(), 1U);
  ASSERT_GT(zones[0].markers.size(), 1U);
  EXPECT_EQ(zones[0].markers[0].action, msg::Marker::DELETEALL);
  for (std::size_t i = 1; i < zones[0].markers.size(); ++i) {
    const auto& z = zones[0].markers[i];
    EXPECT_EQ(std_string(z.header.frame_id), "/sandtray");
    EXPECT_EQ(std_string(z.ns).rfind("sandbox_zone_", 0), 0U);
    EXPECT_DOUBLE_EQ(z.scale.x, 0.005);
  }
  const auto png = of_topic<msg::CompressedImage>(first, topics::kBackground);
  ASSERT_EQ(png.size(), 1U);
  EXPECT_EQ(std_string(png[0].format), "rgba8; png compressed bgr8");
  const auto raw = of_topic<msg::Image>(first, topics::kBackgroundRaw);
  ASSERT_EQ(raw.size(), 1U);
  EXPECT_EQ(raw[0].data.size(), static_cast<std::size_t>(raw[0].width * raw[0].height * 4));
  EXPECT_EQ(raw[0].header.stamp, png[0].header.stamp);
  const auto info = of_topic<msg::CameraInfo>(first, topics::kBackgroundInfo);
  ASSERT_EQ(info.size(), 1U);  // K = [1/pixelscale, 0, w/2; 0, 1/pixelscale, h/2; 0, 0, 1] (§3.6)
  EXPECT_NEAR(info[0].K[0] * sim::kScreenWidthM, raw[0].width, 1e-9);
  EXPECT_DOUBLE_EQ(info[0].K[2], raw[0].width / 2.0);
  EXPECT_DOUBLE_EQ(info[0].K[5], raw[0].height / 2.0);
  EXPECT_TRUE(topics.state(snapshot_at(0.1, *tray)).empty());  // the same background: nothing again
}

TEST(TickTopics, OccupancyMapAtFiveHertzRowsStartAtTheBottomEdge) {
  const auto tray = free_play_tray();
  auto topics = topics_of(kMap);
  const auto maps = of_topic<msg::OccupancyGrid>(topics.state(snapshot_at(0.0, *tray)), topics::kMap);
  ASSERT_EQ(maps.size(), 1U);
  EXPECT_TRUE(topics.state(snapshot_at(0.1, *tray)).empty());
  EXPECT_EQ(topics.state(snapshot_at(0.2, *tray)).size(), 1U);
  const auto& grid = maps[0];
  ASSERT_EQ(grid.data.size(), static_cast<std::size_t>(grid.info.width * grid.info.height));
  EXPECT_DOUBLE_EQ(grid.info.origin.position.y, -0.335);
  // The hippo's centre (0.2, −0.1) is occupied: ROS row = (y − origin_y) / resolution.
  const double resolution = grid.info.resolution;
  const int col = static_cast<int>(0.2 / resolution);
  const int row = static_cast<int>((-0.1 - grid.info.origin.position.y) / resolution);
  EXPECT_EQ(grid.data[static_cast<std::size_t>(row * static_cast<int>(grid.info.width) + col)], 100);
}

TEST(TickTopics, ArmReachCarriesTheDiscRadiusAsZAndCameraLinksAreTheUrdfs) {
  const auto tray = free_play_tray();
  auto topics = topics_of(kArmReach | kCameraLinkFrames);
  runner::ReachDisc disc;
  disc.centre = {0.3, 0.05};
  disc.radius = 0.42;
  EXPECT_TRUE(topics.state(snapshot_at(0.0, *tray)).empty());  // not set: none
  topics.set_arm_reach(disc);
  const auto reach = of_topic<msg::TFMessage>(topics.state(snapshot_at(0.1, *tray)), topics::kTf);
  ASSERT_EQ(reach.size(), 1U);
  EXPECT_EQ(std_string(reach[0].transforms[0].child_frame_id), "arm_reach");
  EXPECT_DOUBLE_EQ(reach[0].transforms[0].transform.translation.z, 0.42);
  const auto links = of_topic<msg::TFMessage>(topics.frames(snapshot_at(0.1, *tray)), topics::kTf);
  ASSERT_EQ(links.size(), 1U);
  EXPECT_EQ(links[0].transforms.size(), 3U);
}

TEST(TickTopics, ATickGoesOutInPublicationOrderAndOnTheFrontsTimeBase) {
  const auto tray = free_play_tray();
  TickTopicsOptions options;
  options.streams = kLiveGraphStreams;
  options.origin_ns = 1700000000ULL * 1000000000ULL;
  TickTopics topics(9, options);
  const auto tick = topics.tick(snapshot_at(0.0, *tray));
  ASSERT_GT(tick.size(), 12U);
  for (std::size_t i = 1; i < tick.size(); ++i) EXPECT_LE(tick[i - 1].published, tick[i].published);
  for (const auto& m : tick) {
    const auto serialized = serialize(m, options.origin_ns);
    EXPECT_EQ(serialized.stamp_ns, topics.stamp_ns(m.published));
    EXPECT_EQ(serialized.stamp_ns / 1000000000ULL, 1700000000ULL);
    EXPECT_FALSE(serialized.bytes->empty());
  }
}

}  // namespace
}  // namespace freeplay::recording
