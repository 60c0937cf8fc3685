// The simulated sandtray: touches, dragging, z-order, robot finger, walls, states, determinism, idle skipping.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::sim {
namespace {

std::shared_ptr<const ItemCatalogue> catalogue() {
  static const auto shared = std::make_shared<const ItemCatalogue>(ItemCatalogue::load_default());
  return shared;
}

SandtrayConfig small_raster() {
  SandtrayConfig config;
  config.raster_width_px = 240;  // keeps canvas work small; physics does not depend on it
  return config;
}

std::unique_ptr<Sandtray> make_tray(std::uint64_t seed = 7, SandtrayConfig config = small_raster()) {
  return std::make_unique<Sandtray>(catalogue(), config, Rng(seed));
}

/// Steps in 1/60 s increments until every body sleeps (or `max_s` passes).
void settle(Sandtray& tray, double max_s = 10.0) {
  for (double t = 0.0; t < max_s && !tray.asleep(); t += kPhysicsStepS) tray.step(kPhysicsStepS);
}

/// Name of an item whose centre is its own top-most point (so a press there grabs it), other than `except`.
std::string grabbable_item(const Sandtray& tray, const std::string& except = {}) {
  for (const auto& item : tray.items()) {
    if (!item.visible || item.name == except) continue;
    const auto hit = tray.item_at(item.pose.position());
    if (hit && *hit == item.name) return item.name;
  }
  return {};
}

bool has_event(const std::vector<Event>& events, const std::string& type, const std::string& key,
               const std::string& value) {
  for (const auto& e : events) {
    if (e.type() == type && e.data().contains(key) && e.data()[key] == value) return true;
  }
  return false;
}

/// Drags `finger` from `from` to `to` at `speed` m/s in 1/60 s steps; returns the largest lag seen.
double drag(Sandtray& tray, int finger, Vec2 from, Vec2 to, double speed) {
  const double length = (to - from).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (speed * kPhysicsStepS))));
  double max_lag = 0.0;
  for (int i = 1; i <= steps; ++i) {
    const Vec2 p = from + (to - from) * (static_cast<double>(i) / steps);
    tray.touch_move(finger, p);
    tray.step(kPhysicsStepS);
    const auto touches = tray.touches();
    const auto item = tray.item(touches.front().item);
    max_lag = std::max(max_lag, (item.pose.position() - p).norm());
  }
  return max_lag;
}

TEST(SandtrayScreen, PixelMetreConversionAndSignOfY) {
  const Vec2 corner = pixel_to_sandtray(kScreenWidthPx, kScreenHeightPx);
  EXPECT_NEAR(corner.x(), 0.6, 1e-12);
  EXPECT_NEAR(corner.y(), -0.335, 1e-12);
  EXPECT_LT(pixel_to_sandtray(100, 200).y(), 0.0) << "pixel rows go down, sandtray y goes up";
  EXPECT_NEAR(kMetresPerPixel, 0.0003125, 1e-15);
  const Vec2 p(0.1234, -0.2345);
  const Vec2 px = sandtray_to_pixel(p);
  EXPECT_NEAR(px.x(), 0.1234 / 0.0003125, 1e-9);
  EXPECT_NEAR(px.y(), 0.2345 / 0.0003125, 1e-9);
  EXPECT_TRUE(on_screen(p));
  EXPECT_FALSE(on_screen(Vec2(0.1, 0.01)));
  EXPECT_TRUE(in_stash(Vec2(0.55, -0.1)));
  EXPECT_FALSE(in_stash(Vec2(0.5, -0.1)));
  EXPECT_DOUBLE_EQ(kPhysicsUnitsPerMetre, kQmlUnitsPerMetre) << "same Box2D scale as the real game";
}

TEST(Sandtray, StartsBlankWithItemsInTheStash) {
  auto tray = make_tray();
  EXPECT_EQ(tray->state(), GameState::Blank);
  EXPECT_EQ(tray->items().size(), 10U);
  const double half_base = kItemBaseSideM / 2.0;
  for (const auto& item : tray->items()) {
    SCOPED_TRACE(item.name);
    EXPECT_GE(item.pose.x, kStashMinX + 10 * kMetresPerPixel + half_base - 1e-12);
    EXPECT_LE(item.pose.x, kStashMinX + 10 * kMetresPerPixel + 0.036 + half_base + 1e-12);
    EXPECT_LE(item.pose.y, -half_base + 1e-12);
    EXPECT_GE(item.pose.y, -(0.9 * kScreenHeightM + half_base) - 1e-12);
    EXPECT_EQ(item.holder.kind, Holder::Kind::None);
  }
  EXPECT_FALSE(tray->item_at(tray->items()[0].pose.position())) << "blank screen: nothing to touch";
  EXPECT_EQ(tray->background_version(), 1U);
}

TEST(Sandtray, GrabDragReleaseMovesTheItemToTheFinger) {
  auto tray = make_tray(3);
  tray->signal(Signal::StartFreeplay);
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  const std::string name = grabbable_item(*tray);
  ASSERT_FALSE(name.empty());
  const Vec2 start = tray->item(name).pose.position();
  ASSERT_EQ(tray->touch_down(1, start), TouchOutcome::GrabbedItem);
  int max_z = 0;
  for (const auto& item : tray->items()) {
    if (item.name != name) max_z = std::max(max_z, item.z);
  }
  EXPECT_EQ(tray->item(name).z, max_z + 1) << "a grabbed item is raised to the top";
  EXPECT_EQ(tray->item(name).holder, (Holder{Holder::Kind::Finger, 1}));
  const Vec2 target = start.x() > 0.3 ? Vec2(0.12, -0.17) : Vec2(0.45, -0.17);
  const double lag = drag(*tray, 1, start, target, 0.25);
  EXPECT_LT(lag, 0.03) << "the item follows a 25 cm/s finger with a small lag";
  EXPECT_GT(lag, 0.003) << "dragging is a spring, not a teleport";
  tray->step(1.0);
  tray->touch_up(1);
  settle(*tray);
  EXPECT_LT((tray->item(name).pose.position() - target).norm(), 0.005);
  EXPECT_EQ(tray->item(name).holder.kind, Holder::Kind::None);
  const auto events = tray->drain_events();
  EXPECT_TRUE(has_event(events, "item_grabbed", "item", name));
  EXPECT_TRUE(has_event(events, "item_released", "item", name));
}

TEST(Sandtray, DragLagMatchesTheSpringModel) {
  // Steady state of a 5 Hz, ζ = 1 mouse joint plus linear damping 5: lag = (2ζω + 5) / ω² × v.
  auto tray = make_tray(4);
  tray->signal(Signal::StartItemsPlacement);  // no item collisions: a clean measurement
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  const std::string name = grabbable_item(*tray);
  const Vec2 start = tray->item(name).pose.position();
  tray->touch_down(2, start);
  const Vec2 target(start.x() > 0.3 ? 0.05 : 0.55, start.y());
  const double speed = 0.25;
  drag(*tray, 2, start, Vec2(start.x() + (target.x() - start.x()) * 0.8, start.y()), speed);
  const double lag = std::abs(tray->item(name).pose.x - tray->touches()[0].position.x());
  const double omega = 2.0 * std::numbers::pi * 5.0;
  EXPECT_NEAR(lag, (2.0 * omega + 5.0) / (omega * omega) * speed, 0.004);
}

TEST(Sandtray, TopMostItemWinsWhenItemsOverlap) {
  auto tray = make_tray(5);
  tray->signal(Signal::StartItemsPlacement);  // items pass through each other
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  const std::string first = grabbable_item(*tray);
  ASSERT_FALSE(first.empty());
  const Vec2 spot(0.25, -0.17);
  tray->touch_down(1, tray->item(first).pose.position());
  drag(*tray, 1, tray->item(first).pose.position(), spot, 0.3);
  tray->step(1.0);
  tray->touch_up(1);
  settle(*tray);
  const std::string second = grabbable_item(*tray, first);
  ASSERT_FALSE(second.empty());
  tray->touch_down(1, tray->item(second).pose.position());
  drag(*tray, 1, tray->item(second).pose.position(), spot, 0.3);
  tray->step(1.0);
  tray->touch_up(1);
  settle(*tray);
  ASSERT_LT((tray->item(first).pose.position() - tray->item(second).pose.position()).norm(), 0.01);
  EXPECT_GT(tray->item(second).z, tray->item(first).z);
  EXPECT_EQ(tray->item_at(spot).value_or(""), second);
  EXPECT_EQ(tray->touch_down(3, spot), TouchOutcome::GrabbedItem);
  EXPECT_EQ(tray->touches()[0].item, second);
}

TEST(Sandtray, RobotFingerReleasesExactlyOneSecondAfterTheLastPose) {
  auto tray = make_tray(6);
  tray->signal(Signal::StartFreeplay);
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  const std::string name = grabbable_item(*tray);
  Vec2 p = tray->item(name).pose.position();
  const Vec2 direction = p.x() > 0.3 ? Vec2(-0.005, 0.0) : Vec2(0.005, 0.0);
  tray->drain_events();
  tray->robot_pose(p);
  EXPECT_EQ(tray->robot_item().value_or(""), name);
  EXPECT_EQ(tray->item(name).holder.kind, Holder::Kind::Robot);
  const int z_before = tray->item(name).z;
  for (int i = 0; i < 20; ++i) {
    tray->step(0.1);
    p += direction;
    tray->robot_pose(p);
  }
  EXPECT_EQ(tray->item(name).z, z_before) << "robot touches do not restack";
  const double last_pose_time = tray->time();
  tray->step(0.99);
  auto events = tray->drain_events();
  EXPECT_FALSE(has_event(events, "interaction_event", "message", "releasing_" + name));
  EXPECT_EQ(tray->robot_item().value_or(""), name);
  tray->step(0.01);
  events = tray->drain_events();
  ASSERT_TRUE(has_event(events, "interaction_event", "message", "releasing_" + name));
  for (const auto& e : events) {
    if (e.type() == "interaction_event") {
      EXPECT_NEAR(e.t, last_pose_time + 1.0, 1e-9);
    }
  }
  EXPECT_TRUE(has_event(events, "item_released", "holder", "robot"));
  EXPECT_FALSE(tray->robot_item());
  EXPECT_FALSE(tray->robot_hand());
  settle(*tray);
  EXPECT_LT((tray->item(name).pose.position() - p).norm(), 0.005) << "the robot dragged the item along";
}

TEST(Sandtray, RobotHoldsOnlyOneItem) {
  auto tray = make_tray(8);
  tray->signal(Signal::StartItemsPlacement);
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  const std::string first = grabbable_item(*tray);
  const std::string second = grabbable_item(*tray, first);
  ASSERT_FALSE(second.empty());
  tray->robot_pose(tray->item(first).pose.position());
  tray->step(0.1);
  tray->robot_pose(tray->item(second).pose.position());
  tray->step(0.1);
  EXPECT_EQ(tray->robot_item().value_or(""), first);
  EXPECT_TRUE(tray->item(second).holders.empty());
  EXPECT_EQ(tray->item(first).holders.size(), 1U);
}

TEST(Sandtray, ChildGrabbingTheRobotsItemSharesItUntilTheRobotLetsGo) {
  auto tray = make_tray(9);
  tray->signal(Signal::StartFreeplay);
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  const std::string name = grabbable_item(*tray);
  const Vec2 p = tray->item(name).pose.position();
  tray->robot_pose(p);
  tray->drain_events();
  ASSERT_EQ(tray->touch_down(4, p), TouchOutcome::GrabbedItem);
  auto events = tray->drain_events();
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].data()["shared_with"][0], "robot");
  const auto holders = tray->item(name).holders;
  ASSERT_EQ(holders.size(), 2U);
  EXPECT_EQ(holders[0], (Holder{Holder::Kind::Finger, 4}));
  EXPECT_EQ(holders[1].kind, Holder::Kind::Robot);
  EXPECT_EQ(tray->item(name).holder, holders[0]);
  for (const ItemState& state : tray->items()) {  // all items at once: the same holders, in the same order
    EXPECT_EQ(state.holders, tray->item(state.name).holders) << state.name;
    EXPECT_EQ(state.holder, tray->item(state.name).holder) << state.name;
  }
  // Both joints act: the item settles between the robot's target and the child's finger.
  const Vec2 child(p.x() > 0.3 ? p.x() - 0.06 : p.x() + 0.06, p.y());
  tray->touch_move(4, child);
  tray->step(0.8);
  const Vec2 between = tray->item(name).pose.position();
  EXPECT_GT((between - p).norm(), 0.01);
  EXPECT_GT((between - child).norm(), 0.01);
  tray->step(0.3);  // the robot's 1 s timer expires; the child keeps the item
  EXPECT_TRUE(has_event(tray->drain_events(), "interaction_event", "message", "releasing_" + name));
  EXPECT_EQ(tray->item(name).holders, (std::vector<Holder>{Holder{Holder::Kind::Finger, 4}}));
  settle(*tray);
  EXPECT_LT((tray->item(name).pose.position() - child).norm(), 0.005);
}

TEST(Sandtray, ItemsNeverLeaveTheScreen) {
  auto tray = make_tray(10);
  tray->signal(Signal::StartFreeplay);
  tray->signal(Signal::ShuffleItems);
  const double tolerance = 0.001;
  const auto check = [&] {
    for (const auto& item : tray->items()) {
      for (const Vec2& v : tray->footprint(item.name)) {
        ASSERT_GE(v.x(), -tolerance) << item.name << " at t=" << tray->time();
        ASSERT_LE(v.x(), kScreenWidthM + tolerance) << item.name << " at t=" << tray->time();
        ASSERT_LE(v.y(), tolerance) << item.name << " at t=" << tray->time();
        ASSERT_GE(v.y(), -kScreenHeightM - tolerance) << item.name << " at t=" << tray->time();
      }
    }
  };
  const Vec2 edges[] = {{0.0, -0.17}, {0.6, -0.17}, {0.3, 0.0}, {0.3, -0.335}, {0.0, 0.0}, {0.6, -0.335}};
  Rng rng(99);
  for (int round = 0; round < 24; ++round) {
    const std::string name = grabbable_item(*tray);
    if (name.empty()) {
      tray->signal(Signal::ShuffleItems);
      continue;
    }
    // Fling: the finger jumps to an edge, the item accelerates at the joint's force limit, then is let go.
    tray->touch_down(1, tray->item(name).pose.position());
    tray->touch_move(1, edges[round % 6]);
    for (int i = 0; i < 12; ++i) {
      tray->step(kPhysicsStepS);
      check();
    }
    tray->touch_up(1);
    for (int i = 0; i < 30; ++i) {
      tray->step(kPhysicsStepS);
      check();
    }
    // The robot pulls an item towards a target far beyond the wall for 2 s.
    if (round % 4 == 0) {
      const std::string pulled = grabbable_item(*tray);
      if (pulled.empty()) continue;
      tray->robot_pose(tray->item(pulled).pose.position());
      for (int i = 0; i < 20; ++i) {
        tray->robot_pose(Vec2(round % 8 == 0 ? 2.0 : -2.0, -rng.uniform(0.0, 0.4)));
        for (int k = 0; k < 6; ++k) {
          tray->step(kPhysicsStepS);
          check();
        }
      }
      tray->step(1.0);
    }
  }
}

/// The same scripted session on a tray; returns the hash after every step.
std::vector<std::uint64_t> scripted_session(std::uint64_t seed) {
  auto tray = make_tray(seed);
  std::vector<std::uint64_t> hashes{tray->state_hash()};
  tray->signal(Signal::StartFreeplay);
  tray->select_colour(PaletteColour::Blue);
  tray->step(0.5);
  hashes.push_back(tray->state_hash());
  const auto first = tray->items().front().pose.position();
  tray->touch_down(1, first);
  tray->touch_down(2, Vec2(0.2, -0.2));
  for (int i = 0; i < 10; ++i) {
    tray->touch_move(1, Vec2(0.4 - 0.01 * i, -0.1));
    tray->touch_move(2, Vec2(0.2 + 0.01 * i, -0.2));
    tray->robot_pose(Vec2(0.3, -0.05 - 0.005 * i));
    tray->step(0.1);
    hashes.push_back(tray->state_hash());
  }
  tray->touch_up(1);
  tray->touch_up(2);
  tray->signal(Signal::ShuffleItems);
  tray->step(2.0);
  hashes.push_back(tray->state_hash());
  return hashes;
}

// A 10 Hz tick without input recomputes no raster: no background copy, no zone segmentation.
TEST(Sandtray, TicksWithoutInputRecomputeNoRaster) {
  auto tray = make_tray(12);
  tray->signal(Signal::StartFreeplay);
  tray->step(1.0);
  const auto before = tray->zone_counters();
  const auto version = tray->background_version();
  for (int tick = 0; tick < 50; ++tick) tray->step(0.1);
  EXPECT_EQ(tray->background_version(), version);
  EXPECT_EQ(tray->zone_counters().images, before.images);
  EXPECT_EQ(tray->zone_counters().masks_recomputed, before.masks_recomputed);
  EXPECT_EQ(tray->zone_counters().rasters_full, before.rasters_full);
  EXPECT_EQ(tray->zone_counters().rasters_windowed, before.rasters_windowed);
  EXPECT_EQ(tray->zone_counters().contour_searches, before.contour_searches);
  EXPECT_EQ(tray->zone_counters().distance_pixels, before.distance_pixels);
  // A stroke changes the background: one more segmentation at the next 4 Hz poll, reusing unchanged masks.
  tray->select_colour(PaletteColour::Red);
  tray->touch_down(1, {0.30, -0.15});
  tray->touch_move(1, {0.34, -0.16});
  tray->touch_up(1);
  for (int tick = 0; tick < 5; ++tick) tray->step(0.1);
  EXPECT_EQ(tray->background_version(), version + 1);
  EXPECT_EQ(tray->zone_counters().images, before.images + 1);
  EXPECT_GT(tray->zone_counters().masks_reused, before.masks_reused);
}

TEST(Sandtray, IdenticalInputsGiveIdenticalStateHashes) {
  EXPECT_EQ(scripted_session(21), scripted_session(21));
  const auto a = scripted_session(21);
  const auto b = scripted_session(22);
  EXPECT_NE(a.front(), b.front()) << "different seeds place the items differently";
  EXPECT_NE(a.back(), b.back());
}

TEST(Sandtray, BadInputThrowsAndChangesNothing) {
  auto tray = make_tray(11);
  tray->signal(Signal::StartFreeplay);
  tray->step(0.3);
  tray->touch_down(2, Vec2(0.1, -0.1));
  const std::uint64_t before = tray->state_hash();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto expect_rejected = [&](const char* what, auto&& call) {
    SCOPED_TRACE(what);
    EXPECT_THROW(call(), InputError);
    EXPECT_EQ(tray->state_hash(), before);
  };
  expect_rejected("seventh finger", [&] { tray->touch_down(7, Vec2(0.2, -0.2)); });
  expect_rejected("finger 0", [&] { tray->touch_down(0, Vec2(0.2, -0.2)); });
  expect_rejected("finger already down", [&] { tray->touch_down(2, Vec2(0.2, -0.2)); });
  expect_rejected("move of a finger that is up", [&] { tray->touch_move(3, Vec2(0.2, -0.2)); });
  expect_rejected("up of a finger that is up", [&] { tray->touch_up(3); });
  expect_rejected("move of finger 9", [&] { tray->touch_move(9, Vec2(0.2, -0.2)); });
  expect_rejected("NaN press", [&] { tray->touch_down(1, Vec2(nan, -0.2)); });
  expect_rejected("inf move", [&] { tray->touch_move(2, Vec2(0.2, -inf)); });
  expect_rejected("press off screen", [&] { tray->touch_down(1, Vec2(0.2, 0.05)); });
  expect_rejected("move off screen", [&] { tray->touch_move(2, Vec2(0.7, -0.1)); });
  expect_rejected("unknown item", [&] { (void)tray->item("unicorn"); });
  expect_rejected("unknown footprint", [&] { (void)tray->footprint("unicorn"); });
  expect_rejected("unknown colour", [&] { tray->select_colour("magenta"); });
  expect_rejected("NaN robot pose", [&] { tray->robot_pose(Vec2(nan, 0.0)); });
  expect_rejected("negative dt", [&] { tray->step(-0.1); });
  expect_rejected("NaN dt", [&] { tray->step(nan); });
  try {
    tray->touch_down(7, Vec2(0.2, -0.2));
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "finger");
    EXPECT_EQ(e.allowed(), "1…6");
  }
}

TEST(Sandtray, TutorialShowsOnlyBoyAndGirl) {
  auto tray = make_tray(12);
  const auto version = tray->background_version();
  tray->signal(Signal::StartTutorial);
  EXPECT_EQ(tray->state(), GameState::Tutorial);
  EXPECT_GT(tray->background_version(), version);
  EXPECT_FALSE(tray->drawing_enabled());
  for (const auto& item : tray->items()) {
    EXPECT_EQ(item.visible, item.name == "boy" || item.name == "girl") << item.name;
    EXPECT_GE(item.pose.x, kStashMinX) << item.name;
  }
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  for (const auto& item : tray->items()) {
    const auto hit = tray->item_at(item.pose.position());
    if (hit) {
      EXPECT_TRUE(*hit == "boy" || *hit == "girl") << "hidden items cannot be touched";
    }
  }
}

TEST(Sandtray, FreeplayPutsEverythingInTheStashAndEnablesDrawing) {
  auto tray = make_tray(13);
  tray->signal(Signal::ShuffleItems);
  tray->signal(Signal::StartFreeplay);
  EXPECT_TRUE(tray->drawing_enabled());
  for (const auto& item : tray->items()) {
    EXPECT_TRUE(item.visible);
    EXPECT_TRUE(in_stash(item.pose.position())) << item.name;
  }
  EXPECT_EQ(tray->touch_down(1, Vec2(0.2, -0.2)), TouchOutcome::StartedStroke);
  EXPECT_TRUE(tray->frames().has("touch1"));
}

TEST(Sandtray, ItemsPlacementHidesGirlAndCaravanAndDisablesCollisions) {
  auto tray = make_tray(14);
  tray->signal(Signal::StartItemsPlacement);
  EXPECT_FALSE(tray->drawing_enabled());
  for (const auto& item : tray->items()) {
    EXPECT_EQ(item.visible, item.name != "girl" && item.name != "caravan") << item.name;
  }
  EXPECT_EQ(tray->touch_down(1, Vec2(0.2, -0.2)), TouchOutcome::Ignored) << "no drawing in items placement";
  EXPECT_FALSE(tray->frames().has("touch1")) << "an idle finger publishes no frame";
}

TEST(Sandtray, ShuffleKeepsItemsInTheCentralEightyPercent) {
  auto tray = make_tray(15);
  tray->signal(Signal::StartFreeplay);
  for (int round = 0; round < 20; ++round) {
    tray->signal(Signal::ShuffleItems);
    for (const auto& item : tray->items()) {
      EXPECT_GE(item.pose.x, 0.1 * kScreenWidthM);
      EXPECT_LE(item.pose.x, 0.9 * kScreenWidthM);
      EXPECT_LE(item.pose.y, -0.1 * kScreenHeightM);
      EXPECT_GE(item.pose.y, -0.9 * kScreenHeightM);
    }
  }
  tray->signal(Signal::ItemsToStash);
  for (const auto& item : tray->items()) EXPECT_TRUE(in_stash(item.pose.position())) << item.name;
}

TEST(Sandtray, IdleTrayTakesNoPhysicsSteps) {
  auto tray = make_tray(16);
  tray->signal(Signal::StartFreeplay);
  settle(*tray, 30.0);
  ASSERT_TRUE(tray->asleep());
  const auto steps = tray->physics_steps();
  const double t0 = tray->time();
  const auto ticks = tray->tick_count();
  for (int i = 0; i < 100; ++i) tray->step(0.1);
  EXPECT_EQ(tray->physics_steps(), steps);
  EXPECT_NEAR(tray->time(), t0 + 10.0, 1e-9);
  EXPECT_EQ(tray->tick_count(), ticks + 100);
  const std::string name = grabbable_item(*tray);
  tray->touch_down(1, tray->item(name).pose.position());
  tray->touch_move(1, Vec2(0.3, -0.2));
  tray->step(0.1);
  EXPECT_GT(tray->physics_steps(), steps) << "a drag wakes the world";
}

TEST(Sandtray, EveryCallThatMayMoveAnItemCountsAsAnInput) {
  // SimWorld refills its item snapshot only when input_count moved: a mutator that forgot to count would leave it
  // stale.
  auto tray = make_tray(18);
  auto count = tray->input_count();
  const auto counts = [&](const char* what) {
    EXPECT_GT(tray->input_count(), count) << what;
    count = tray->input_count();
  };
  tray->signal(Signal::StartFreeplay);
  counts("signal");
  tray->step(0.1);
  counts("step");
  const std::string name = grabbable_item(*tray);
  const Vec2 at = tray->item(name).pose.position();
  tray->touch_down(1, at);
  counts("touch_down");
  tray->touch_move(1, Vec2(0.3, -0.15));
  counts("touch_move");
  tray->touch_up(1);
  counts("touch_up");
  tray->robot_pose(Vec2(0.3, -0.2));
  counts("robot_pose");
  tray->place_item(name, Pose2{0.2, -0.2, 0.0});
  counts("place_item");
  const auto snapshot = tray->items();
  (void)tray->item(name);
  (void)tray->touches();
  (void)tray->state_hash();
  (void)tray->drain_events();
  tray->select_colour(PaletteColour::Eraser);
  EXPECT_EQ(tray->input_count(), count) << "reads, event draining and the brush colour move no item";
}

TEST(Sandtray, FramesAndFootprints) {
  auto tray = make_tray(17);
  tray->signal(Signal::StartFreeplay);
  tray->step(0.2);
  FrameTree frames = tray->frames();
  for (const auto& item : tray->items()) {
    const auto pose = frames.lookup("sandtray", item.name);
    ASSERT_TRUE(pose);
    EXPECT_NEAR(pose->translation().x(), item.pose.x, 1e-12);
    EXPECT_NEAR(pose->translation().y(), item.pose.y, 1e-12);
    const auto footprint = tray->footprint(item.name);
    const auto& spec = tray->catalogue().get(item.name);
    EXPECT_NEAR((footprint[0] - item.pose.to_parent(spec.polygon[0])).norm(), 0.0, 1e-12);
  }
  EXPECT_FALSE(frames.has("touch1"));
  for (const auto& [name, polygon] : tray->published_footprints()) {
    EXPECT_LT(vertex_mean(polygon).norm(), 1e-12) << name;
  }
}

TEST(Sandtray, BackgroundIsRepublishedAtMostFourTimesASecondAfterStrokes) {
  auto tray = make_tray(18);
  tray->signal(Signal::StartFreeplay);
  tray->select_colour(PaletteColour::Red);
  tray->step(0.3);
  const auto version = tray->background_version();
  tray->touch_down(1, Vec2(0.1, -0.1));
  for (int i = 0; i < 5; ++i) {
    tray->touch_move(1, Vec2(0.1 + 0.01 * i, -0.1));
    tray->step(0.1);
  }
  EXPECT_EQ(tray->background_version(), version) << "an unfinished stroke is not published";
  tray->touch_up(1);
  tray->step(0.25);
  EXPECT_EQ(tray->background_version(), version + 1);
  tray->step(2.0);
  EXPECT_EQ(tray->background_version(), version + 1) << "nothing changed, nothing published";
  // Many short strokes: publications stay <= 4 Hz.
  const auto start = tray->background_version();
  for (int i = 0; i < 40; ++i) {
    tray->touch_down(2, Vec2(0.05 + 0.01 * i, -0.25));
    tray->touch_move(2, Vec2(0.06 + 0.01 * i, -0.26));
    tray->touch_up(2);
    tray->step(0.05);
  }
  EXPECT_LE(tray->background_version() - start, 9U);
  EXPECT_GE(tray->background_version() - start, 7U);
  tray->signal(Signal::ClearDrawing);
  tray->step(0.25);
  EXPECT_GT(tray->background_version(), start + 7);
}

}  // namespace
}  // namespace freeplay::sim

namespace freeplay::sim {
namespace {

TEST(SandtrayRobot, RepeatedIdenticalPosesDoNotRestartTheTimer) {
  // The real subscriber ignores position changes under 0.5 px: a robot that repeats one pose lets go after 1 s.
  auto tray = make_tray(19);
  tray->signal(Signal::StartFreeplay);
  tray->signal(Signal::ShuffleItems);
  settle(*tray);
  const std::string name = grabbable_item(*tray);
  const Vec2 p = tray->item(name).pose.position();
  tray->robot_pose(p);
  for (int i = 0; i < 9; ++i) {
    tray->step(0.1);
    tray->robot_pose(p + Vec2(0.0001, 0.0));  // 0.32 px: below the real EPSILON
  }
  tray->step(0.1);
  EXPECT_FALSE(tray->robot_item()) << "released 1.0 s after the first pose";
  EXPECT_TRUE(has_event(tray->drain_events(), "interaction_event", "message", "releasing_" + name));
}

TEST(SandtrayRobot, PosesAreIgnoredOnTheBlankScreenAndOffItemsGrabNothing) {
  auto tray = make_tray(20);
  const Vec2 p = tray->items().front().pose.position();
  tray->robot_pose(p);
  EXPECT_FALSE(tray->robot_item());
  EXPECT_FALSE(tray->robot_hand());
  tray->signal(Signal::StartFreeplay);
  tray->robot_pose(Vec2(0.1, -0.1));
  EXPECT_FALSE(tray->robot_item());
  ASSERT_TRUE(tray->robot_hand());
  EXPECT_NEAR(tray->robot_hand()->x(), 0.1, 1e-12);
  tray->step(1.0);
  EXPECT_FALSE(tray->robot_hand()) << "the hand disappears with the release timer";
}

TEST(SandtrayScreenImage, RendersTheScreenAtTheRequestedWidth) {
  auto tray = make_tray(21);
  tray->signal(Signal::StartFreeplay);
  const cv::Mat screen = tray->render_screen(480);
  EXPECT_EQ(screen.cols, 480);
  EXPECT_EQ(screen.rows, 268);
  EXPECT_EQ(screen.type(), CV_8UC3);
  EXPECT_EQ(tray->background().cols, 240) << "the published background has the raster width";
  EXPECT_GT(tray->zones().zones().size(), 0U) << "the map background has colour zones";
}

}  // namespace
}  // namespace freeplay::sim

namespace freeplay::sim {
namespace {

// The tick's item snapshot into a reused vector equals items() and, once sized, keeps its storage (no allocation).
TEST(Sandtray, ItemSnapshotIntoAReusedVectorKeepsItsStorage) {
  auto tray = make_tray(5);
  tray->signal(Signal::StartFreeplay);
  tray->signal(Signal::ShuffleItems);
  tray->step(0.5);
  const auto target = tray->items().front();
  tray->touch_down(1, target.pose.position());
  tray->touch_down(2, target.pose.position());
  std::vector<ItemState> snapshot;
  tray->items(snapshot);
  const ItemState* storage = snapshot.data();
  const Holder* holders = snapshot.front().holders.data();
  ASSERT_EQ(snapshot.front().holders.size(), 2u);
  for (int tick = 0; tick < 10; ++tick) {
    tray->touch_move(1, target.pose.position() + Vec2(0.002 * tick, 0.0));
    tray->step(0.1);
    tray->items(snapshot);
    const auto fresh = tray->items();
    ASSERT_EQ(snapshot.size(), fresh.size());
    for (std::size_t i = 0; i < fresh.size(); ++i) {
      EXPECT_EQ(snapshot[i].name, fresh[i].name);
      EXPECT_EQ(snapshot[i].pose.x, fresh[i].pose.x);
      EXPECT_EQ(snapshot[i].pose.theta, fresh[i].pose.theta);
      EXPECT_EQ(snapshot[i].holders, fresh[i].holders);
      EXPECT_EQ(snapshot[i].holder, fresh[i].holder);
    }
    EXPECT_EQ(snapshot.data(), storage);
    EXPECT_EQ(snapshot.front().holders.data(), holders);
  }
  EXPECT_EQ(tray->item(target.name).holders, snapshot.front().holders);
}

}  // namespace
}  // namespace freeplay::sim
