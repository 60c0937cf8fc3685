#include <gtest/gtest.h>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/session.hpp"
#include "freeplay/core/error.hpp"

using namespace freeplay;
using namespace freeplay::agents;

TEST(Annotations, WritesThePinsoroLayout) {
  SessionAnnotations a;
  a.purple = ChildTimeline{{Axis::TaskEngagement, 3, 0.0, 1.5},
                           {Axis::SocialEngagement, 0, 0.0, 4.0},
                           {Axis::TaskEngagement, 0, 1.5, 4.0}};
  a.yellow = ChildTimeline{{Axis::SocialAttitude, 4, 0.0, 4.0}};
  const std::string text = to_pinsoro_yaml(a, 100.0, "Annotations made by test on the 1st");
  EXPECT_EQ(text,
            "# Annotations made by test on the 1st\n"
            "purple:\n"
            "  - noplay: [100, 101.5]\n"
            "  - solitary: [100, 104]\n"
            "  - goaloriented: [101.5, 104]\n"
            "yellow:\n"
            "  - passive: [100, 104]\n");
}

TEST(Annotations, SimulatedSessionRoundTrips) {
  const ChildModelParams params = default_child_model_params();
  const SessionResult session = simulate_session(params, SessionConfig{}, 7);
  SessionAnnotations a;
  a.purple = session.purple.timeline;
  a.yellow = session.yellow->timeline;
  const double base = 1495118000.25;  // a ROS epoch time base, as in the real files
  const SessionAnnotations back = parse_pinsoro_yaml(to_pinsoro_yaml(a, base), "a.yaml", base);
  ASSERT_TRUE(back.purple && back.yellow);
  ASSERT_EQ(back.purple->size(), a.purple->size());
  for (std::size_t i = 0; i < a.purple->size(); ++i) {
    EXPECT_EQ((*back.purple)[i].axis, (*a.purple)[i].axis);
    EXPECT_EQ((*back.purple)[i].label, (*a.purple)[i].label);
    EXPECT_NEAR((*back.purple)[i].start, (*a.purple)[i].start, 1e-6);
    EXPECT_NEAR((*back.purple)[i].stop, (*a.purple)[i].stop, 1e-6);
  }
  // Each axis tiles the whole session without gaps.
  for (const Axis axis : kAxes) {
    double covered = 0.0;
    for (const auto& bout : *back.yellow) covered += bout.axis == axis ? bout.stop - bout.start : 0.0;
    EXPECT_NEAR(covered, session.duration_s, 1e-3);
  }
}

TEST(Annotations, ChildRobotSessionsHaveNoYellow) {
  SessionConfig config;
  config.condition = Condition::ChildRobot;
  const SessionResult session = simulate_session(default_child_model_params(), config, 3);
  EXPECT_FALSE(session.yellow);
  SessionAnnotations a;
  a.purple = session.purple.timeline;
  const std::string text = to_pinsoro_yaml(a);
  EXPECT_EQ(text.find("yellow"), std::string::npos);
  EXPECT_FALSE(parse_pinsoro_yaml(text).yellow);
}

TEST(Annotations, BadInputNamesTheLine) {
  try {
    (void)parse_pinsoro_yaml("purple:\n  - noplay: [0, 1]\n  - bored: [1, 2]\n", "x.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(e.allowed().find("cooperative"), std::string::npos);
  }
  EXPECT_THROW((void)parse_pinsoro_yaml("purple:\n  - noplay: [2, 1]\n"), InputError);
  EXPECT_THROW((void)parse_pinsoro_yaml("green:\n  - noplay: [0, 1]\n"), InputError);
  EXPECT_THROW((void)parse_pinsoro_yaml("purple:\n  - noplay: [0]\n"), InputError);
  // The annotator's conflict placeholder is accepted and skipped.
  EXPECT_EQ(parse_pinsoro_yaml("purple:\n  - '?': [0, 1]\n  - noplay: [0, 1]\n").purple->size(), 1U);
}
