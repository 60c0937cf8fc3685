#include <gtest/gtest.h>

#include <set>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/asocial.hpp"

using namespace freeplay;
using namespace freeplay::policies;

namespace {

ZoneObservation square_zone(const std::string& colour, Vec2 centre, double half) {
  ZoneObservation z;
  z.colour = colour;
  z.polygon = {centre + Vec2(-half, -half), centre + Vec2(half, -half), centre + Vec2(half, half),
               centre + Vec2(-half, half)};
  z.centroid = vertex_mean(z.polygon);
  return z;
}

Observation tray_with(std::vector<ItemObservation> items, std::vector<ZoneObservation> zones) {
  Observation o;
  o.items = std::move(items);
  o.zones = std::move(zones);
  return o;
}

ItemObservation item(const std::string& name, double x, double y) {
  ItemObservation i;
  i.name = name;
  i.pose = {x, y, 0.0};
  return i;
}

}  // namespace

TEST(Asocial, HabitatsTableIsTheOriginal) {
  const auto& h = asocial_habitats();
  EXPECT_EQ(h.at("zebra"), (std::vector<std::string>{"yellow", "green"}));
  EXPECT_EQ(h.at("elephant"), (std::vector<std::string>{"green"}));
  EXPECT_EQ(h.at("lion"), (std::vector<std::string>{"yellow"}));
  EXPECT_EQ(h.at("crocodile"), (std::vector<std::string>{"blue"}));
  EXPECT_EQ(h.at("hippo"), (std::vector<std::string>{"blue"}));
  EXPECT_EQ(h.at("girl"), (std::vector<std::string>{"yellow", "green", "purple", "white"}));
  EXPECT_EQ(asocial_item_order().size(), 10u);
}

TEST(Asocial, MovesAnItemOutOfItsHabitatToTheClosestCentroidOfTheColour) {
  AsocialPolicy policy({});
  policy.reset({}, Rng(3));
  // The hippo is on grass; two blue zones, the nearer at (0.2, -0.1).
  const auto obs = tray_with({item("hippo", 0.1, -0.1)},
                             {square_zone("green", {0.1, -0.1}, 0.05), square_zone("blue", {0.2, -0.1}, 0.02),
                              square_zone("blue", {0.45, -0.3}, 0.02)});
  const auto move = policy.choose_move(obs);
  ASSERT_TRUE(move.has_value());
  EXPECT_EQ(move->item, "hippo");
  EXPECT_TRUE(move->target.isApprox(Vec2(0.2, -0.1)));
}

TEST(Asocial, SkipsItemsAlreadyHomeAndItemsOutOfReach) {
  AsocialPolicy policy({});
  policy.reset({}, Rng(4));
  auto obs = tray_with({item("crocodile", 0.2, -0.1), item("elephant", 0.55, -0.3)},
                       {square_zone("blue", {0.2, -0.1}, 0.03), square_zone("green", {0.1, -0.25}, 0.03)});
  obs.self.arm_reach_known = true;
  obs.self.arm_reach_centre = {0.2, -0.05};
  obs.self.arm_reach_radius = 0.25;  // elephant at (0.55, -0.3) is out of reach
  EXPECT_FALSE(policy.choose_move(obs).has_value());
  obs.self.arm_reach_radius = 0.6;  // now reachable, and the green centroid too
  const auto move = policy.choose_move(obs);
  ASSERT_TRUE(move.has_value());
  EXPECT_EQ(move->item, "elephant");
}

TEST(Asocial, AnItemOnAHabitatsEdgeIsHomeAndJustOutsideIsNot) {
  // The bounding-box prefilter must keep point_in_polygon's answer on and near the boundary.
  const auto zone = square_zone("blue", {0.2, -0.1}, 0.03);
  for (const Vec2& p : {Vec2(0.23, -0.1), Vec2(0.17, -0.13), Vec2(0.2, -0.07)}) {
    AsocialPolicy policy({});
    policy.reset({}, Rng(7));
    EXPECT_FALSE(policy.choose_move(tray_with({item("hippo", p.x(), p.y())}, {zone})).has_value()) << p.transpose();
  }
  for (const Vec2& p : {Vec2(0.23 + 1e-7, -0.1), Vec2(0.2, -0.13 - 1e-7)}) {
    AsocialPolicy policy({});
    policy.reset({}, Rng(7));
    EXPECT_TRUE(policy.choose_move(tray_with({item("hippo", p.x(), p.y())}, {zone})).has_value()) << p.transpose();
  }
}

TEST(Asocial, UnreachableCentroidsAreNotTargets) {
  AsocialPolicy policy({});
  policy.reset({}, Rng(5));
  auto obs = tray_with({item("lion", 0.2, -0.1)},
                       {square_zone("yellow", {0.25, -0.1}, 0.01), square_zone("yellow", {0.55, -0.3}, 0.01)});
  obs.self.arm_reach_known = true;
  obs.self.arm_reach_centre = {0.2, -0.1};
  obs.self.arm_reach_radius = 0.1;
  const auto move = policy.choose_move(obs);
  ASSERT_TRUE(move.has_value());
  EXPECT_TRUE(move->target.isApprox(Vec2(0.25, -0.1)));
}

TEST(Asocial, PausesUniformlyBetween1_2And2_5SecondsAfterAMove) {
  AsocialPolicy policy({});
  policy.reset({}, Rng(6));
  auto obs = tray_with({item("hippo", 0.1, -0.1)}, {square_zone("blue", {0.3, -0.2}, 0.02)});
  std::vector<double> gaps;
  double t = 0.0;
  double result_at = -1.0;
  for (int tick = 0; tick < 20000 && gaps.size() < 200; ++tick, t += 0.01) {
    obs.t = t;
    const auto actions = policy.decide(obs);
    if (!actions.empty()) {
      if (result_at >= 0) gaps.push_back(t - result_at);
      policy.on_result({ActionResult::Kind::MoveSucceeded, "hippo", ""});
      result_at = t;  // the move "finishes" at once
    }
  }
  ASSERT_GE(gaps.size(), 100u);
  double lo = 1e9;
  double hi = 0.0;
  for (const double g : gaps) {
    lo = std::min(lo, g);
    hi = std::max(hi, g);
  }
  EXPECT_GE(lo, 1.2 - 1e-9);
  EXPECT_LE(hi, 2.5 + 0.02 + 1e-9);  // + two 10 ms ticks of decision granularity
  EXPECT_LT(lo, 1.4);                // spread over the whole interval
  EXPECT_GT(hi, 2.3);
}

TEST(Asocial, ChecksAgainAfter0_3SecondsWhenNothingToDo) {
  AsocialPolicy policy({});
  policy.reset({}, Rng(7));
  auto obs = tray_with({item("hippo", 0.3, -0.2)}, {square_zone("blue", {0.3, -0.2}, 0.02)});  // already home
  obs.t = 0.0;
  EXPECT_TRUE(policy.decide(obs).empty());
  obs.items[0].pose = {0.1, -0.1, 0.0};  // the child moves it away
  obs.t = 0.29;
  EXPECT_TRUE(policy.decide(obs).empty());
  obs.t = 0.3;
  EXPECT_EQ(policy.decide(obs).size(), 1u);
}

TEST(Asocial, DoesNotCheckWhetherAChildHoldsTheItemLikeTheOriginal) {
  AsocialPolicy policy({});
  policy.reset({}, Rng(8));
  auto obs = tray_with({item("hippo", 0.1, -0.1)}, {square_zone("blue", {0.3, -0.2}, 0.02)});
  obs.items[0].touched_by_child = true;
  EXPECT_TRUE(policy.choose_move(obs).has_value());
}

TEST(Asocial, RejectsBadParameters) {
  EXPECT_THROW(AsocialPolicy(YAML::Load("{pause_min_s: 3, pause_max_s: 1}")), InputError);
  EXPECT_THROW(AsocialPolicy(YAML::Load("{pause: 3}")), InputError);
}

// The parameters are one settings struct (core/settings_archive.hpp): its initialisers are the original's pauses, and
// a bad value names its key under `robot.params` with the allowed range or keys.
TEST(Asocial, ParametersDefaultToTheOriginalAndNameTheBadKey) {
  const AsocialParams defaults;
  EXPECT_DOUBLE_EQ(defaults.pause_min_s, 1.2);
  EXPECT_DOUBLE_EQ(defaults.pause_max_s, 2.5);
  EXPECT_DOUBLE_EQ(defaults.idle_pause_s, 0.3);
  EXPECT_NO_THROW(AsocialPolicy(YAML::Node()));
  EXPECT_NO_THROW(AsocialPolicy(YAML::Load("{pause_min_s: 0.5}")));
  const auto message_of = [](const char* params) {
    try {
      AsocialPolicy policy{YAML::Load(params)};
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string range = message_of("{idle_pause_s: 61}");
  EXPECT_NE(range.find("'robot.params.idle_pause_s'"), std::string::npos) << range;
  EXPECT_NE(range.find("[0, 60]"), std::string::npos) << range;
  const std::string unknown = message_of("{pause: 3}");
  EXPECT_NE(unknown.find("allowed: pause_min_s, pause_max_s, idle_pause_s"), std::string::npos) << unknown;
  const std::string order = message_of("{pause_min_s: 3}");  // above the default upper bound
  EXPECT_NE(order.find("pause_max_s is below pause_min_s"), std::string::npos) << order;
}
