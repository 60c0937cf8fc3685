#pragma once
// A `move_sandbox_items` actionlib client for the live tests, in this process's ROS node (compiled as C++17 beside
// the message headers, as ros/src/graph; this header holds only standard types).

#include <string>
#include <vector>

namespace freeplay::ros_test {

/// How one goal went, as its client saw it.
struct GoalOutcome {
  bool server = false;         ///< the server answered within the timeout
  bool finished = false;       ///< a result arrived within the timeout
  std::string state;           ///< actionlib's terminal state ("SUCCEEDED", "ABORTED", "PREEMPTED", …)
  std::string text;            ///< the goal's status text
  std::vector<int> feedback;   ///< the feedback percentages received, in order
};

/// Sends one goal (move `item` to (x, y) in `sandtray`) to `move_sandbox_items` and waits at most `timeout_s` wall
/// seconds for the server and as long again for the result; start_ros must have run in this process.
GoalOutcome send_move_goal(const std::string& item, double x, double y, double timeout_s);

/// Shuts this process's ROS node down (before the test stops its master).
void shutdown_ros();

}  // namespace freeplay::ros_test
