#include <gtest/gtest.h>

#include "freeplay/agents/labels.hpp"

using namespace freeplay::agents;

TEST(Labels, ExactStringsOfTheCodingScheme) {
  EXPECT_EQ(name(TaskEngagement::GoalOriented), "goaloriented");
  EXPECT_EQ(name(TaskEngagement::Aimless), "aimless");
  EXPECT_EQ(name(TaskEngagement::AdultSeeking), "adultseeking");
  EXPECT_EQ(name(TaskEngagement::NoPlay), "noplay");
  EXPECT_EQ(name(SocialEngagement::Solitary), "solitary");
  EXPECT_EQ(name(SocialEngagement::Onlooker), "onlooker");
  EXPECT_EQ(name(SocialEngagement::Parallel), "parallel");
  EXPECT_EQ(name(SocialEngagement::Associative), "associative");
  EXPECT_EQ(name(SocialEngagement::Cooperative), "cooperative");
  EXPECT_EQ(name(SocialAttitude::Prosocial), "prosocial");
  EXPECT_EQ(name(SocialAttitude::Adversarial), "adversarial");
  EXPECT_EQ(name(SocialAttitude::Assertive), "assertive");
  EXPECT_EQ(name(SocialAttitude::Frustrated), "frustrated");
  EXPECT_EQ(name(SocialAttitude::Passive), "passive");
  EXPECT_EQ(axis_name(Axis::TaskEngagement), "task_engagement");
  EXPECT_EQ(axis_name(Axis::SocialEngagement), "social_engagement");
  EXPECT_EQ(axis_name(Axis::SocialAttitude), "social_attitude");
}

TEST(Labels, ParseRoundTripsAndRejectsOthers) {
  for (const Axis axis : kAxes) {
    for (std::size_t i = 0; i < label_count(axis); ++i) {
      const auto parsed = parse_label(label_name(axis, i));
      ASSERT_TRUE(parsed);
      EXPECT_EQ(parsed->first, axis);
      EXPECT_EQ(parsed->second, i);
    }
  }
  EXPECT_FALSE(parse_label("goal-oriented"));
  EXPECT_FALSE(parse_label("Cooperative"));
  EXPECT_FALSE(parse_label("?"));
  EXPECT_THROW((void)label_name(Axis::TaskEngagement, 4), std::out_of_range);
}

TEST(Labels, InitialStateIsTheAnnotatorReset) {
  const LabelState state;
  EXPECT_EQ(state.task, TaskEngagement::NoPlay);
  EXPECT_EQ(state.social, SocialEngagement::Solitary);
  EXPECT_EQ(state.attitude, SocialAttitude::Passive);
}
