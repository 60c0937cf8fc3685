// The freeplay_sandbox_msgs generated at build time are the real ones: same MD5 sums, types and definitions.
#include <freeplay_sandbox_msgs/AttentionTargetsStamped.h>
#include <freeplay_sandbox_msgs/PlaygroundNavigationAction.h>
#include <freeplay_sandbox_msgs/PlaygroundPlan.h>
#include <gtest/gtest.h>

#include <string>

namespace {

TEST(RosMessages, Md5SumsMatchTheRealFreeplaySandboxMsgs) {
  using namespace freeplay_sandbox_msgs;
  EXPECT_EQ(std::string(ros::message_traits::md5sum<PlaygroundNavigationAction>()), "963b23f6d5b652b667fa543b37887490");
  EXPECT_EQ(std::string(ros::message_traits::md5sum<PlaygroundNavigationGoal>()), "2ed089e571e800686ee1fc2035ee705c");
  EXPECT_EQ(std::string(ros::service_traits::md5sum<PlaygroundPlan>()), "961b128a52b8c2470af3bee566e33af5");
}

TEST(RosMessages, TypesAndFieldsAreTheRealOnes) {
  using namespace freeplay_sandbox_msgs;
  EXPECT_EQ(std::string(ros::message_traits::datatype<PlaygroundNavigationGoal>()),
            "freeplay_sandbox_msgs/PlaygroundNavigationGoal");
  EXPECT_EQ(std::string(ros::service_traits::datatype<PlaygroundPlan>()), "freeplay_sandbox_msgs/PlaygroundPlan");
  PlaygroundNavigationGoal goal;
  goal.item = "hippo";
  goal.goal.x = 0.3;
  PlaygroundNavigationFeedback feedback;
  feedback.percentage = 50;
  EXPECT_EQ(goal.item, "hippo");
  EXPECT_EQ(AttentionTarget::DEICTIC_GESTURE, 1);
  EXPECT_EQ(AttentionTarget::NONVERBAL_UTTERANCE, 4);
}

}  // namespace
