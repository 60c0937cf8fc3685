#pragma once
// The ROS 1 message types the recorder writes, usable from C++20: Debian's generated headers name
// `ContainerAllocator::rebind`, which std::allocator lost in C++20, so every message is instantiated with
// RosAllocator (std::allocator plus rebind). The bag stores the standard type names, MD5 sums and definitions.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "freeplay/core/error.hpp"

namespace freeplay::recording {

/// While a message is read from a bag (read_message), the number of bytes it holds; 0 otherwise (no limit).
inline thread_local std::size_t g_message_bytes_being_read = 0;

/// Thrown when a message being read asks for a container longer than the message itself.
struct CorruptLength : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// std::allocator with the `rebind` member the ROS 1 message headers expect. While a message is read from a bag it
/// refuses a container longer than the message's bytes: ROS's deserialiser resizes a vector to the stored length
/// before it reads the elements, so a corrupt length would otherwise ask for up to 2^32 of them.
template <class T>
struct RosAllocator : std::allocator<T> {
  using value_type = T;
  RosAllocator() = default;
  /// Converting constructor (allocators of every type are interchangeable).
  template <class U>
  RosAllocator(const RosAllocator<U>& /*other*/) noexcept {}
  /// Storage for `n` values. Every element of a stored container takes at least one of the message's bytes (a
  /// string of `n` characters, allocated with its terminator, at least four more for its length).
  T* allocate(std::size_t n) {
    if (g_message_bytes_being_read != 0 && n > g_message_bytes_being_read) {
      throw CorruptLength("a container of " + std::to_string(n) + " elements in a message of " +
                          std::to_string(g_message_bytes_being_read) + " bytes");
    }
    return std::allocator<T>::allocate(n);
  }
  /// The same allocator for another type.
  template <class U>
  struct rebind {
    using other = RosAllocator<U>;
  };
};

}  // namespace freeplay::recording

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Empty.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

namespace freeplay::recording::msg {

using Allocator = RosAllocator<void>;
using String = std_msgs::String_<Allocator>;                        ///< std_msgs/String
using Empty = std_msgs::Empty_<Allocator>;                          ///< std_msgs/Empty
using Header = std_msgs::Header_<Allocator>;                        ///< std_msgs/Header
using TFMessage = tf2_msgs::TFMessage_<Allocator>;                  ///< tf2_msgs/TFMessage
using TransformStamped = geometry_msgs::TransformStamped_<Allocator>;  ///< geometry_msgs/TransformStamped
using PoseStamped = geometry_msgs::PoseStamped_<Allocator>;         ///< geometry_msgs/PoseStamped
using Point = geometry_msgs::Point_<Allocator>;                     ///< geometry_msgs/Point
using Quaternion = geometry_msgs::Quaternion_<Allocator>;           ///< geometry_msgs/Quaternion
using CompressedImage = sensor_msgs::CompressedImage_<Allocator>;   ///< sensor_msgs/CompressedImage
using Image = sensor_msgs::Image_<Allocator>;                       ///< sensor_msgs/Image
using OccupancyGrid = nav_msgs::OccupancyGrid_<Allocator>;          ///< nav_msgs/OccupancyGrid
using CameraInfo = sensor_msgs::CameraInfo_<Allocator>;             ///< sensor_msgs/CameraInfo
using JointState = sensor_msgs::JointState_<Allocator>;             ///< sensor_msgs/JointState
using Marker = visualization_msgs::Marker_<Allocator>;              ///< visualization_msgs/Marker
using MarkerArray = visualization_msgs::MarkerArray_<Allocator>;    ///< visualization_msgs/MarkerArray
using RosString = String::_data_type;                               ///< the string type inside messages

}  // namespace freeplay::recording::msg

namespace freeplay::recording {

/// A ROS string from a std::string_view.
inline msg::RosString ros_string(std::string_view text) { return msg::RosString(text.begin(), text.end()); }
/// Message `m` of a bag as type `M`, every container's stored length checked against the message's size: a corrupt
/// length is an InputError naming the topic instead of a multi-gigabyte allocation, and so is a message of another type
/// (rosbag returns none). rosbag's own errors pass through.
template <class M>
boost::shared_ptr<M> read_message(const rosbag::MessageInstance& m) {
  struct Reading {
    explicit Reading(std::size_t bytes) { g_message_bytes_being_read = bytes; }
    ~Reading() { g_message_bytes_being_read = 0; }
    Reading(const Reading&) = delete;
    Reading& operator=(const Reading&) = delete;
  } reading(m.size());
  boost::shared_ptr<M> message;
  try {
    message = m.instantiate<M>();
  } catch (const CorruptLength& e) {
    throw InputError(std::string("corrupt message: ") + e.what(), m.getTopic(), "a ROS 1 bag written by `freeplay run --record`");
  }
  if (!message) {  // rosbag answers a type or MD5 sum other than M's with no message
    throw InputError("a message of type " + m.getDataType() + " (MD5 " + m.getMD5Sum() + ")", m.getTopic(),
                     std::string(ros::message_traits::DataType<M>::value()) + " (MD5 " + ros::message_traits::MD5Sum<M>::value() + ")");
  }
  return message;
}

/// A std::string from a ROS string.
inline std::string std_string(const msg::RosString& text) { return std::string(text.begin(), text.end()); }

/// The fixed ROS time of the sandtray clock's origin: every stamp is `kEpochS + t` (2017-07-14 02:40:00 UTC, in
/// the PInSoRo campaign's year), so that a session's bag is identical from run to run.
inline constexpr double kEpochS = 1500000000.0;
/// ROS time of sandtray time `t` (s).
ros::Time ros_time(double t);
/// Sandtray time (s) of a ROS time.
double sandtray_time(const ros::Time& stamp);

/// A rosbag::Bag that may be made, opened, closed and destroyed from several threads at once: Debian's rosbag loads
/// its encryptor plugin through class_loader, which is not thread-safe (parallel recordings crashed), so those four
/// steps hold one process-wide lock. Reading and writing an open bag need no lock.
class Bag {
 public:
  /// An unopened bag.
  Bag();
  /// Closes the bag if it is open.
  ~Bag();
  Bag(const Bag&) = delete;
  Bag& operator=(const Bag&) = delete;

  /// Opens `path` in `mode` (rosbag::bagmode); rosbag's exceptions pass through.
  void open(const std::string& path, std::uint32_t mode);
  /// Closes the bag (writes the index when writing).
  void close();
  /// The rosbag bag, for writing and for rosbag::View.
  rosbag::Bag& get() { return *bag_; }

 private:
  std::unique_ptr<rosbag::Bag> bag_;
};

/// Opens the bag of a session folder (`freeplay.bag`, else `freeplay.bag.active`) or a bag file for reading and
/// returns its path; InputError when there is none or it is unreadable (unindexed: says to run `rosbag reindex`).
std::filesystem::path open_session_bag(const std::filesystem::path& path, Bag& bag);

}  // namespace freeplay::recording
