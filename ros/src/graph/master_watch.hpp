#pragma once
// Watches the ROS master from a thread of its own (internal to freeplay_ros_graph). A roscpp node keeps its peer
// connections when the master goes away, but never registers again with a master that comes back; the graphs ask
// this watch and register their topics and servers anew after a restart.

#include <atomic>
#include <thread>

namespace freeplay::ros_graph {

/// Polls `ros::master::check()` twice a second; logs when the master goes away and comes back.
class MasterWatch {
 public:
  MasterWatch();
  ~MasterWatch();
  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

  /// How many times the master came back after being away (0 until the first restart).
  int returns() const { return returns_.load(); }
  /// True while the master answers.
  bool up() const { return up_.load(); }

 private:
  void watch();
  std::atomic<bool> stop_{false};
  std::atomic<bool> up_{true};
  std::atomic<int> returns_{0};
  std::thread thread_;
};

}  // namespace freeplay::ros_graph
