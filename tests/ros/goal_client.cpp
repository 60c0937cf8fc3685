#include "goal_client.hpp"

#include <actionlib/client/simple_action_client.h>
#include <freeplay_sandbox_msgs/PlaygroundNavigationAction.h>
#include <ros/ros.h>

#include <mutex>

namespace freeplay::ros_test {

GoalOutcome send_move_goal(const std::string& item, double x, double y, double timeout_s) {
  using Client = actionlib::SimpleActionClient<freeplay_sandbox_msgs::PlaygroundNavigationAction>;
  GoalOutcome out;
  Client client("move_sandbox_items", true);  // its own callback queue and spin thread
  out.server = client.waitForServer(ros::Duration(timeout_s));
  if (!out.server) return out;
  freeplay_sandbox_msgs::PlaygroundNavigationGoal goal;
  goal.item = item;
  goal.goal.x = x;
  goal.goal.y = y;
  std::mutex mutex;
  client.sendGoal(goal, Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                  [&](const freeplay_sandbox_msgs::PlaygroundNavigationFeedbackConstPtr& feedback) {
                    std::lock_guard<std::mutex> lock(mutex);
                    out.feedback.push_back(feedback->percentage);
                  });
  out.finished = client.waitForResult(ros::Duration(timeout_s));
  std::lock_guard<std::mutex> lock(mutex);
  out.state = client.getState().toString();
  out.text = client.getState().getText();
  return out;
}

void shutdown_ros() { ros::shutdown(); }

}  // namespace freeplay::ros_test
