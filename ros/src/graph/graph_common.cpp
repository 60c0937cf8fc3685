// Starting the ROS client once per process, and the wall clock.
#include <ros/ros.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <mutex>
#include <thread>

#include "freeplay/ros/graph.hpp"
#include "master_watch.hpp"

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
  ros::start();  // started here, the node outlives its node handles (the graphs renew theirs after a restart)
  return true;
}

MasterWatch::MasterWatch() : thread_([this] { watch(); }) {}

MasterWatch::~MasterWatch() {
  stop_ = true;
  thread_.join();
}

void MasterWatch::watch() {
  constexpr auto kPeriod = std::chrono::milliseconds(500);
  while (!stop_) {
    const bool now_up = ros::master::check();
    if (now_up != up_.load()) {
      if (now_up) {
        spdlog::warn("the ROS master at {} is back: registering again", ros::master::getURI());
        ++returns_;
      } else {
        spdlog::warn("lost the ROS master at {}: running on (existing connections stay) until it is back",
                     ros::master::getURI());
      }
      up_ = now_up;
    }
    for (auto slept = std::chrono::milliseconds(0); slept < kPeriod && !stop_; slept += std::chrono::milliseconds(50)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
}

double wall_now() { return ros::WallTime::now().toSec(); }

}  // namespace freeplay::ros_graph
