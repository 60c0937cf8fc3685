// The simulated game as the live graph's messages: frames at the items' centres, footprints in the items' frames,
// zones as zones_from_image, the background and the occupancy map as the real nodes lay them out.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "freeplay/planning/occupancy_grid.hpp"
#include "freeplay/ros/graph_messages.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::ros_live {
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

TEST(GraphMessages, ItemFramesAreAtTheCentresWithTheirYaw) {
  const auto tray = free_play_tray();
  const auto frames = game_frames(*tray);
  ASSERT_EQ(frames.size(), 10U);  // no finger down: items only
  for (const auto& f : frames) {
    EXPECT_EQ(f.parent, "sandtray");
    if (f.child != "hippo") continue;
    EXPECT_NEAR(f.translation[0], 0.2, 1e-9);
    EXPECT_NEAR(f.translation[1], -0.1, 1e-9);
    EXPECT_NEAR(rotation_yaw(f.rotation), 0.5, 1e-9);
  }
  tray->touch_down(2, {0.5, -0.3});
  const auto with_touch = game_frames(*tray);
  ASSERT_EQ(with_touch.size(), 11U);
  EXPECT_EQ(with_touch.back().child, "touch2");
}

TEST(GraphMessages, FootprintsAreClosedPolygonsInTheItemsFrames) {
  const auto tray = free_play_tray();
  const auto markers = footprint_markers(*tray);
  ASSERT_EQ(markers.size(), 10U);
  for (const auto& m : markers) {
    EXPECT_EQ(m.frame, "/" + m.ns);
    ASSERT_GE(m.points.size(), 4U);
    EXPECT_EQ(m.points.front(), m.points.back());
  }
}

TEST(GraphMessages, ZonesAndBackgroundFollowTheRealNodes) {
  const auto tray = free_play_tray();
  const auto zones = zone_markers(*tray);
  ASSERT_FALSE(zones.empty());
  for (const auto& z : zones) {
    EXPECT_EQ(z.frame, "/sandtray");
    EXPECT_EQ(z.ns.rfind("sandbox_zone_", 0), 0U);
    EXPECT_DOUBLE_EQ(z.width, 0.005);
  }
  const auto image = background_image(*tray);
  EXPECT_EQ(image.rgba.size(), static_cast<std::size_t>(image.width * image.height * 4));
  EXPECT_NEAR(image.pixel2meter * image.width, sim::kScreenWidthM, 1e-12);
  EXPECT_FALSE(image.png.empty());
}

TEST(GraphMessages, OccupancyMapRowsStartAtTheBottomEdge) {
  const auto tray = free_play_tray();
  const auto grid = occupancy_map(*tray);
  ASSERT_EQ(grid.cells.size(), static_cast<std::size_t>(grid.width * grid.height));
  EXPECT_DOUBLE_EQ(grid.origin_y, -0.335);
  // The hippo's centre (0.2, −0.1) is occupied: ROS row = (y − origin_y) / resolution.
  const int col = static_cast<int>(0.2 / grid.resolution);
  const int row = static_cast<int>((-0.1 - grid.origin_y) / grid.resolution);
  EXPECT_EQ(grid.cells[static_cast<std::size_t>(row * grid.width + col)], 100);
}

TEST(GraphMessages, ArmReachFrameCarriesTheDiscRadiusAsZ) {
  runner::ReachDisc disc;
  disc.centre = {0.3, 0.05};
  disc.radius = 0.42;
  const auto f = arm_reach_frame(disc);
  EXPECT_EQ(f.child, "arm_reach");
  EXPECT_DOUBLE_EQ(f.translation[2], 0.42);
  EXPECT_EQ(camera_links().size(), 3U);
}

}  // namespace
}  // namespace freeplay::ros_live
