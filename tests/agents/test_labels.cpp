#include <gtest/gtest.h>

#include "freeplay/agents/labels.hpp"

using namespace freeplay::agents;

TEST(Labels, ExactStrings) {
  EXPECT_EQ(name(TaskEngagement::GoalOriented), "goaloriented");
}
