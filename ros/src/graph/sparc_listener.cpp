#include "freeplay/ros/sparc_listener.hpp"

#include <geometry_msgs/PoseStamped.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

namespace freeplay::ros_live {

struct SparcListener::Impl {
  ros::CallbackQueue queue;
  ros::NodeHandle node;
  ros::Subscriber subscriber;
  ros::AsyncSpinner spinner{1, &queue};
};

SparcListener::SparcListener(Handler handler) : impl_(std::make_unique<Impl>()) {
  impl_->node.setCallbackQueue(&impl_->queue);
  impl_->subscriber = impl_->node.subscribe<geometry_msgs::PoseStamped>(
      "sparc/selected_action", 10, [handler = std::move(handler)](const geometry_msgs::PoseStamped::ConstPtr& msg) {
        std::string item = msg->header.frame_id;
        if (!item.empty() && item.front() == '/') item.erase(0, 1);
        handler(item, msg->pose.position.x, msg->pose.position.y);
      });
  impl_->spinner.start();
}

SparcListener::~SparcListener() {
  impl_->spinner.stop();
  impl_->subscriber.shutdown();
}

}  // namespace freeplay::ros_live
