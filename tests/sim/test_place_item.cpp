// The setup-only teleport `Sandtray::place_item`: exact placement at rest, strong guarantee on bad input.

#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::sim {
namespace {

std::unique_ptr<Sandtray> free_play_tray() {
  static const auto catalogue = std::make_shared<const ItemCatalogue>(ItemCatalogue::load_default());
  SandtrayConfig config;
  config.raster_width_px = 240;
  auto tray = std::make_unique<Sandtray>(catalogue, config, Rng(3));
  tray->signal(Signal::StartFreeplay);
  return tray;
}

TEST(PlaceItem, PutsTheItemAtThePoseAtRest) {
  auto tray = free_play_tray();
  tray->place_item("hippo", Pose2{0.30, -0.17, 0.4});
  const ItemState hippo = tray->item("hippo");
  EXPECT_NEAR(hippo.pose.x, 0.30, 1e-6);
  EXPECT_NEAR(hippo.pose.y, -0.17, 1e-6);
  EXPECT_NEAR(hippo.pose.theta, 0.4, 1e-6);
  tray->step(1.0);  // nothing else is there: it stays put
  EXPECT_NEAR(tray->item("hippo").pose.x, 0.30, 1e-6);
  EXPECT_EQ(tray->item_at({0.30, -0.17}), std::optional<std::string>("hippo"));
}

TEST(PlaceItem, BadInputThrowsAndChangesNothing) {
  auto tray = free_play_tray();
  const auto before = tray->state_hash();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(tray->place_item("unicorn", Pose2{0.3, -0.1, 0.0}), InputError);
  EXPECT_THROW(tray->place_item("hippo", Pose2{nan, -0.1, 0.0}), InputError);
  EXPECT_THROW(tray->place_item("hippo", Pose2{0.3, -0.1, nan}), InputError);
  EXPECT_THROW(tray->place_item("hippo", Pose2{0.7, -0.1, 0.0}), InputError);
  EXPECT_THROW(tray->place_item("hippo", Pose2{0.3, 0.05, 0.0}), InputError);
  EXPECT_EQ(tray->state_hash(), before);

  tray->place_item("hippo", Pose2{0.30, -0.17, 0.0});
  ASSERT_EQ(tray->touch_down(1, {0.30, -0.17}), TouchOutcome::GrabbedItem);
  const auto held = tray->state_hash();
  EXPECT_THROW(tray->place_item("hippo", Pose2{0.1, -0.1, 0.0}), InputError);
  EXPECT_EQ(tray->state_hash(), held);
}

}  // namespace
}  // namespace freeplay::sim
