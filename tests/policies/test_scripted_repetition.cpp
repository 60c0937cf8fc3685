// The scripted policy's timetables: `every` repeats an action from `t`, `until` ends the repetition.

#include <gtest/gtest.h>

#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"

using namespace freeplay;
using namespace freeplay::policies;

namespace {

/// The free-play times (at the 10 Hz decision ticks up to `end_s`) at which `policy` started an action, with the
/// action's index in the variant (0 move, 1 look, 2 point, 3 say, 4 wait, 5 cancel).
std::vector<std::pair<double, std::size_t>> fired(PlayPolicy& policy, double end_s) {
  policy.reset({}, Rng(1));
  std::vector<std::pair<double, std::size_t>> out;
  Observation obs;
  for (long tick = 0; static_cast<double>(tick) * 0.1 <= end_s + 1e-9; ++tick) {
    obs.t = static_cast<double>(tick) * 0.1;
    for (const auto& a : policy.decide(obs)) out.emplace_back(obs.t, a.index());
  }
  return out;
}

std::string error_of(const std::string& params) {
  try {
    make_policy("scripted", YAML::Load(params));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ScriptedRepetition, EveryRepeatsFromTUntilTheEnd) {
  auto policy = make_policy("scripted", YAML::Load(R"(
actions:
  - {t: 1, every: 15, say: {text: "Wow!"}}
  - {t: 2, every: 5, until: 12, look_at: {child: purple}}
)"));
  const auto times = fired(*policy, 50.0);
  const std::vector<std::pair<double, std::size_t>> expected = {
      {1.0, 3}, {2.0, 1}, {7.0, 1}, {12.0, 1}, {16.0, 3}, {31.0, 3}, {46.0, 3}};
  ASSERT_EQ(times.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(times[i].first, expected[i].first, 1e-9) << i;
    EXPECT_EQ(times[i].second, expected[i].second) << i;
  }
}

TEST(ScriptedRepetition, WithoutUntilTheTimetableNeverEnds) {
  auto policy = make_policy("scripted", YAML::Load("actions: [{t: 0, every: 15, say: {text: Wow!}}]"));
  EXPECT_EQ(fired(*policy, 2400.0).size(), 161u);  // t = 0, 15, …, 2400
}

TEST(ScriptedRepetition, ALateTickCatchesUpInTimeOrder) {
  // A coarse caller (one decision after 10 s) gets every occurrence due by then, earliest first.
  auto policy = make_policy("scripted", YAML::Load(R"(
actions:
  - {t: 0, every: 4, say: {text: a}}
  - {t: 1, every: 4, point_at: [0.1, -0.2]}
)"));
  policy->reset({}, Rng(1));
  Observation obs;
  obs.t = 10.0;
  const auto due = policy->decide(obs);
  ASSERT_EQ(due.size(), 6u);  // say 0, point 1, say 4, point 5, say 8, point 9
  for (std::size_t i = 0; i < due.size(); ++i) EXPECT_EQ(due[i].index(), i % 2 == 0 ? 3u : 2u) << i;
  EXPECT_TRUE(policy->decide(obs).empty());
}

TEST(ScriptedRepetition, ResetStartsTheTimetableAgain) {
  auto policy = make_policy("scripted", YAML::Load("actions: [{t: 1, every: 2, until: 5, cancel: true}]"));
  EXPECT_EQ(fired(*policy, 10.0).size(), 3u);
  EXPECT_EQ(fired(*policy, 10.0).size(), 3u);
}

TEST(ScriptedRepetition, BadRepetitionsNameTheKeyAndTheAllowedValues) {
  const auto zero = error_of("actions: [{t: 1, every: 0, say: {text: a}}]");
  EXPECT_NE(zero.find("actions[0].every"), std::string::npos) << zero;
  EXPECT_NE(zero.find("0.1"), std::string::npos) << zero;
  const auto text = error_of("actions: [{t: 1, every: often, say: {text: a}}]");
  EXPECT_NE(text.find("every"), std::string::npos) << text;
  const auto alone = error_of("actions: [{t: 1, until: 5, say: {text: a}}]");
  EXPECT_NE(alone.find("actions[0].until"), std::string::npos) << alone;
  EXPECT_NE(alone.find("needs `every`"), std::string::npos) << alone;
  const auto early = error_of("actions: [{t: 10, every: 1, until: 5, say: {text: a}}]");
  EXPECT_NE(early.find("actions[0].until"), std::string::npos) << early;
  EXPECT_NE(early.find("≥ t (10)"), std::string::npos) << early;
}
