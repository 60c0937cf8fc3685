#include <gtest/gtest.h>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"

using namespace freeplay;
using namespace freeplay::policies;

namespace {

Observation base_tray() {
  Observation o;
  const char* names[] = {"zebra", "elephant", "giraffe", "hippo", "lion", "crocodile"};
  double x = 0.05;
  for (const char* n : names) {
    ItemObservation i;
    i.name = n;
    i.pose = {x, -0.15, 0.0};
    x += 0.07;
    o.items.push_back(i);
  }
  ZoneObservation green;
  green.colour = "green";
  green.polygon = {{0.0, -0.335}, {0.5, -0.335}, {0.5, 0.0}, {0.0, 0.0}};
  green.centroid = vertex_mean(green.polygon);
  o.zones.push_back(green);
  PerceivedChild child;
  child.seat = "purple";
  child.face_detected = true;
  child.seconds_since_touch = 1.0;
  o.children.push_back(child);
  return o;
}

template <typename T>
std::vector<T> of_type(const std::vector<Action>& actions) {
  std::vector<T> out;
  for (const auto& a : actions) {
    if (std::holds_alternative<T>(a)) out.push_back(std::get<T>(a));
  }
  return out;
}

}  // namespace

TEST(SocialPolicy, NeverMovesAnItemAChildHolds) {
  // Over many seeds and situations, no MoveItem names an item the child is touching.
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    auto policy = make_policy("social", YAML::Load("{join_probability: 1.0, idle_proposal_s: 1, disengaged_s: 2}"));
    policy->reset({}, Rng(seed));
    auto o = base_tray();
    o.children[0].seconds_since_touch = 100.0;  // idle child: the robot proposes moves by example
    for (int tick = 0; tick < 300; ++tick) {
      o.t = tick * 0.1;
      // The child holds the zebra, then the hippo, alternating.
      for (auto& item : o.items) item.touched_by_child = (item.name == (tick / 50 % 2 ? "hippo" : "zebra"));
      o.children[0].moving_item = tick / 50 % 2 ? "hippo" : "zebra";
      for (const auto& move : of_type<MoveItem>(policy->decide(o))) {
        const auto* item = o.item(move.item);
        ASSERT_NE(item, nullptr);
        EXPECT_FALSE(item->touched_by_child) << "seed " << seed << " moved " << move.item;
        policy->on_result({ActionResult::Kind::MoveSucceeded, move.item, ""});
      }
    }
  }
}

TEST(SocialPolicy, ReactsToAChildsMoveWithPraiseAndAJoiningMove) {
  auto policy = make_policy("social", YAML::Load("{praise_probability: 1.0, join_probability: 1.0}"));
  policy->reset({}, Rng(1));
  auto o = base_tray();
  o.t = 0.0;
  o.items[0].touched_by_child = true;  // the child grabs the zebra…
  policy->decide(o);
  o.t = 0.5;
  o.items[0].touched_by_child = false;  // …and drops it 10 cm away
  o.items[0].pose.x += 0.10;
  EXPECT_TRUE(of_type<MoveItem>(policy->decide(o)).empty());  // reaction delay
  std::vector<Action> reaction;
  for (int tick = 1; tick <= 10 && reaction.empty(); ++tick) {
    o.t = 0.5 + tick * 0.1;
    reaction = policy->decide(o);
  }
  ASSERT_EQ(of_type<Say>(reaction).size(), 1u);
  const auto moves = of_type<MoveItem>(reaction);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_NE(moves[0].item, "zebra");
  EXPECT_LT((moves[0].target - o.items[0].pose.position()).norm(), 0.1);  // joins near the child's item
}

TEST(SocialPolicy, LooksAtAChildWhoAddressesIt) {
  auto policy = make_policy("social");
  policy->reset({}, Rng(2));
  auto o = base_tray();
  o.children[0].speaking = true;
  o.children[0].addressing_robot = true;
  const auto looks = of_type<LookAt>(policy->decide(o));
  ASSERT_EQ(looks.size(), 1u);
  EXPECT_EQ(looks[0].child.value_or(""), "purple");
}

TEST(SocialPolicy, ProposesAnIdeaWhenTheChildIsIdle) {
  auto policy = make_policy("social", YAML::Load("{idle_proposal_s: 10, disengaged_s: 100}"));
  policy->reset({}, Rng(3));
  auto o = base_tray();
  o.children[0].seconds_since_touch = 12.0;
  o.t = 30.0;
  const auto said = of_type<Say>(policy->decide(o));
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].addressee, "purple");
}

// The parameters are one settings struct read through core/settings_archive.hpp: a bad value names its key under
// `robot.params` with the allowed range or keys.
TEST(Social, BadParametersNameTheKey) {
  const auto message_of = [](const char* params) {
    try {
      make_policy("social", YAML::Load(params));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string range = message_of("{join_probability: 2}");
  EXPECT_NE(range.find("'robot.params.join_probability'"), std::string::npos) << range;
  EXPECT_NE(range.find("[0, 1]"), std::string::npos) << range;
  const std::string unknown = message_of("{delay: 1}");
  EXPECT_NE(unknown.find("allowed: reaction_delay_s, praise_probability, join_probability, idle_proposal_s, "
                         "disengaged_s, turn_timeout_s, join_offset_m, min_move_m"),
            std::string::npos)
      << unknown;
  EXPECT_EQ(message_of("{}"), "no error");
}
