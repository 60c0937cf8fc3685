#pragma once
// Where each stage camera's frames go in a bag (the real drivers' topic and frame names) and how they are
// compressed (image_transport's `compressed` JPEG and `compressedDepth` PNG formats).

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/stage/renderer.hpp"

namespace freeplay::recording {

/// The topics and frames of one camera as the real drivers publish them.
struct CameraTopics {
  std::string rgb_image;      ///< sensor_msgs/CompressedImage (JPEG)
  std::string rgb_info;       ///< sensor_msgs/CameraInfo of the colour stream
  std::string rgb_frame;      ///< optical frame of the colour stream
  std::string rgb_format;     ///< CompressedImage.format the real transport writes
  std::string depth_image;    ///< sensor_msgs/CompressedImage (compressedDepth PNG)
  std::string depth_info;     ///< sensor_msgs/CameraInfo of the depth stream
  std::string depth_frame;    ///< optical frame of the depth stream
};

/// Topics of a stage camera: camera_purple / camera_yellow (RealSense SR300 driver), env_camera (kinect2_bridge,
/// qhd), CameraTop / CameraBottom (naoqi_driver's front/bottom cameras); InputError listing them (the real setup's
/// cameras, stage::real_camera_names()) otherwise.
CameraTopics camera_topics(std::string_view camera);

/// The 12-byte header compressed_depth_image_transport puts before the PNG (codec.h ConfigHeader).
struct CompressedDepthConfigHeader {
  std::int32_t format = 0;          ///< compressionFormat: INV_DEPTH = 0 (the value the 16UC1 path leaves)
  float depth_param[2] = {0, 0};    ///< quantisation parameters (unused by the 16UC1 path: zeros)
};
static_assert(sizeof(CompressedDepthConfigHeader) == 12, "compressed_depth_image_transport's ConfigHeader");

/// JPEG of an R,G,B CV_8UC3 image as compressed_image_transport writes it (the format string is the caller's).
std::vector<std::uint8_t> encode_jpeg(const cv::Mat& rgb, int quality);
/// R,G,B CV_8UC3 image of a compressed colour message (JPEG or PNG); InputError when it does not decode.
cv::Mat decode_colour(const msg::CompressedImage& image);
/// compressedDepth payload of metric depth: ConfigHeader + PNG of 16UC1 millimetres (0 = no reading: non-finite,
/// non-positive or beyond 65.535 m), as compressed_depth_image_transport encodes a 16UC1 image.
std::vector<std::uint8_t> encode_compressed_depth(const cv::Mat& depth_m, int png_level);
/// The 16UC1 millimetre image of a compressedDepth message; InputError when the format is not 16UC1 PNG.
cv::Mat decode_compressed_depth(const msg::CompressedImage& image);

/// sensor_msgs/CameraInfo of a pinhole camera (plumb_bob, no distortion, R = I, P = [K | 0]).
msg::CameraInfo camera_info(const stage::CameraIntrinsics& K, const std::string& frame, const ros::Time& stamp);

}  // namespace freeplay::recording
