#include "freeplay/recording/camera_topics.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/camera_names.hpp"

namespace freeplay::recording {

CameraTopics camera_topics(std::string_view camera) {
  const std::string name(camera);
  if (name == "camera_purple" || name == "camera_yellow") {  // realsense driver + image_transport (dual_sr300.launch)
    // Relative names, as the real bags store them (free-play-sandbox.md §4.1).
    return {name + "/rgb/image_raw/compressed", name + "/rgb/camera_info", name + "_rgb_optical_frame",
            "rgb8; jpeg compressed bgr8", name + "/depth/image_raw/compressedDepth", name + "/depth/camera_info",
            name + "_depth_optical_frame"};
  }
  if (name == "env_camera") {  // kinect2_bridge, base_name env_camera, qhd stream
    return {"env_camera/qhd/image_color/compressed", "env_camera/qhd/camera_info", "env_camera_rgb_optical_frame",
            "bgr8; jpeg compressed bgr8", "env_camera/sd/image_depth/compressedDepth", "env_camera/sd/camera_info",
            "env_camera_ir_optical_frame"};
  }
  if (name == "CameraTop" || name == "CameraBottom") {  // naoqi_driver's front / bottom cameras
    const std::string which = name == "CameraTop" ? "front" : "bottom";
    return {"/naoqi_driver/camera/" + which + "/image_raw/compressed", "/naoqi_driver/camera/" + which + "/camera_info",
            name + "_optical_frame", "rgb8; jpeg compressed bgr8",
            "/naoqi_driver/camera/depth/image_raw/compressedDepth", "/naoqi_driver/camera/depth/camera_info",
            name + "_optical_frame"};
  }
  throw InputError(fmt::format("camera '{}' has no recorded topics", name), "camera",
                   fmt::format("{}", fmt::join(stage::real_camera_names(), ", ")));
}

std::vector<std::uint8_t> encode_jpeg(const cv::Mat& rgb, int quality) {
  if (rgb.empty() || rgb.type() != CV_8UC3) throw InputError("a colour frame must be a non-empty CV_8UC3 image", "rgb");
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<std::uint8_t> out;
  cv::imencode(".jpg", bgr, out, {cv::IMWRITE_JPEG_QUALITY, quality});
  return out;
}

cv::Mat decode_colour(const msg::CompressedImage& image) {
  const cv::Mat bgr = cv::imdecode(cv::Mat(1, static_cast<int>(image.data.size()), CV_8UC1,
                                           const_cast<std::uint8_t*>(image.data.data())),
                                   cv::IMREAD_COLOR);
  if (bgr.empty()) throw InputError("a compressed colour image does not decode", "format", std_string(image.format));
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return rgb;
}

std::vector<std::uint8_t> encode_compressed_depth(const cv::Mat& depth_m, int png_level) {
  if (depth_m.empty() || depth_m.type() != CV_32FC1) {
    throw InputError("a depth frame must be a non-empty CV_32FC1 image in metres", "depth_m");
  }
  cv::Mat mm(depth_m.size(), CV_16UC1);
  for (int r = 0; r < depth_m.rows; ++r) {
    const float* in = depth_m.ptr<float>(r);
    auto* out = mm.ptr<std::uint16_t>(r);
    for (int c = 0; c < depth_m.cols; ++c) {
      const double v = static_cast<double>(in[c]) * 1000.0;  // NaN fails both comparisons
      out[c] = v > 0.0 && v <= 65535.0 ? static_cast<std::uint16_t>(v + 0.5) : std::uint16_t{0};
    }
  }
  std::vector<std::uint8_t> png;
  cv::imencode(".png", mm, png, {cv::IMWRITE_PNG_COMPRESSION, png_level});
  const CompressedDepthConfigHeader header;
  std::vector<std::uint8_t> data(sizeof header + png.size());
  std::memcpy(data.data(), &header, sizeof header);
  std::memcpy(data.data() + sizeof header, png.data(), png.size());
  return data;
}

cv::Mat decode_compressed_depth(const msg::CompressedImage& image) {
  const auto format = std_string(image.format);
  if (format.rfind("16UC1; compressedDepth", 0) != 0 || image.data.size() <= sizeof(CompressedDepthConfigHeader)) {
    throw InputError(fmt::format("'{}' is not a 16UC1 compressedDepth image", format), "format",
                     "16UC1; compressedDepth");
  }
  const auto payload = static_cast<int>(image.data.size() - sizeof(CompressedDepthConfigHeader));
  cv::Mat mm = cv::imdecode(cv::Mat(1, payload, CV_8UC1,
                                    const_cast<std::uint8_t*>(image.data.data() + sizeof(CompressedDepthConfigHeader))),
                            cv::IMREAD_UNCHANGED);
  if (mm.empty() || mm.type() != CV_16UC1) throw InputError("a compressedDepth PNG does not decode to 16UC1", "data");
  return mm;
}

msg::CameraInfo camera_info(const stage::CameraIntrinsics& K, const std::string& frame, const ros::Time& stamp) {
  msg::CameraInfo info;
  info.header.stamp = stamp;
  info.header.frame_id = ros_string(frame);
  info.width = static_cast<std::uint32_t>(K.width);
  info.height = static_cast<std::uint32_t>(K.height);
  info.distortion_model = ros_string("plumb_bob");
  info.D.assign(5, 0.0);
  info.K = {K.fx, 0.0, K.cx, 0.0, K.fy, K.cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {K.fx, 0.0, K.cx, 0.0, 0.0, K.fy, K.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

}  // namespace freeplay::recording
