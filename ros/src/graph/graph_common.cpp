// Starting the ROS client once per process, and the wall clock.
#include <ros/ros.h>

#include <chrono>
#include <mutex>
#include <thread>

#include "freeplay/ros/graph.hpp"

namespace freeplay::ros_graph {

bool start_ros(const std::string& node_name, double timeout_s, std::string& error) {
  static std::once_flag once;
  std::call_once(once, [&] {
    int argc = 0;
    // Our own SIGINT handling (the commands stop cleanly); no rosout aggregation needed.
    ros::init(argc, nullptr, node_name, ros::init_options::NoSigintHandler);
  });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!ros::master::check()) {
    if (std::chrono::steady_clock::now() > deadline) {
      error = "no ROS master at " + ros::master::getURI() + " (start roscore or set ROS_MASTER_URI)";
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return true;
}

double wall_now() { return ros::WallTime::now().toSec(); }

}  // namespace freeplay::ros_graph
