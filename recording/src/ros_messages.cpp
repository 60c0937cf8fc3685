#include "freeplay/recording/ros_messages.hpp"

#include <cmath>
#include <mutex>

namespace freeplay::recording {

ros::Time ros_time(double t) {
  const double ns = std::round(t * 1e9);
  const auto total = static_cast<std::int64_t>(kEpochS) * 1000000000LL + static_cast<std::int64_t>(ns);
  ros::Time stamp;
  stamp.fromNSec(static_cast<std::uint64_t>(total));
  return stamp;
}

double sandtray_time(const ros::Time& stamp) {
  const auto ns = static_cast<std::int64_t>(stamp.toNSec()) - static_cast<std::int64_t>(kEpochS) * 1000000000LL;
  return static_cast<double>(ns) * 1e-9;
}

namespace {

std::mutex& bag_lifecycle_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

Bag::Bag() {
  std::lock_guard lock(bag_lifecycle_mutex());
  // Every rosbag::Bag loads its encryptor plugin through class_loader, and the last one to go unloads it: one Bag
  // kept for the process (never destroyed, so nothing runs after class_loader's own statics at exit) keeps the
  // library loaded, so a session's bag neither reloads it nor relinks its symbols, nor leaves glibc's atexit records
  // of each reload behind (which made libFuzzer leak-scan every fuzz_bag input).
  [[maybe_unused]] static const rosbag::Bag* const keeps_the_encryptor_plugin_loaded = new rosbag::Bag();
  bag_ = std::make_unique<rosbag::Bag>();
}

Bag::~Bag() {
  std::lock_guard lock(bag_lifecycle_mutex());
  bag_.reset();
}

void Bag::open(const std::string& path, std::uint32_t mode) {
  std::lock_guard lock(bag_lifecycle_mutex());
  bag_->open(path, mode);
}

void Bag::close() {
  std::lock_guard lock(bag_lifecycle_mutex());
  bag_->close();
}

}  // namespace freeplay::recording
