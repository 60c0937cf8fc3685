#pragma once
// The real Wizard-of-Oz GUI's output on a live ROS 1 graph: `sparc/selected_action` (geometry_msgs/PoseStamped,
// `header.frame_id` = the dropped item's name, the pose the drop point in that item's frame, as woz_play converted it
// to `sandtray` through TF). `freeplay serve --web --web-ros` hands each message to the web session's robot.

#include <functional>
#include <memory>
#include <string>

namespace freeplay::ros_live {

/// Subscribes to `sparc/selected_action` while it lives (call ros_graph::start_ros first).
class SparcListener {
 public:
  /// Called on a ROS thread for each message: the item (frame_id without a leading '/') and the drop point in
  /// that item's frame (m).
  using Handler = std::function<void(const std::string& item, double x, double y)>;

  explicit SparcListener(Handler handler);
  ~SparcListener();
  SparcListener(const SparcListener&) = delete;
  SparcListener& operator=(const SparcListener&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace freeplay::ros_live
