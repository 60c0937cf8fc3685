#include "freeplay/recording/session_videos.hpp"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

namespace freeplay::recording {

std::string raw_video_name(const std::string& camera) {
  const std::string name = camera == "env_camera" ? "camera_env" : camera;
  return name + "_raw.mkv";
}

/// One camera's video being written.
struct SessionVideos::Video {
  std::filesystem::path final_path;
  std::filesystem::path partial_path;
  cv::VideoWriter writer;
  cv::Size size;
  cv::Mat bgr;
};

SessionVideos::SessionVideos(std::filesystem::path session_dir, std::map<std::string, double> rates_hz)
    : dir_(std::move(session_dir) / "video"), rates_hz_(std::move(rates_hz)) {}

SessionVideos::~SessionVideos() { discard(); }

void SessionVideos::write(const std::string& camera, const cv::Mat& rgb) {
  if (rgb.empty() || rgb.type() != CV_8UC3) return;  // the bag's image encoder reports a malformed image
  auto& video = videos_[camera];
  if (!video) {
    video = std::make_unique<Video>();
    std::filesystem::create_directories(dir_);
    video->final_path = dir_ / raw_video_name(camera);
    // FFmpeg picks the container from the extension, so the partial file keeps ".mkv".
    video->partial_path = dir_ / (raw_video_name(camera).substr(0, raw_video_name(camera).size() - 4) + ".partial.mkv");
    video->size = rgb.size();
    const auto rate = rates_hz_.find(camera);
    const double fps = rate != rates_hz_.end() ? rate->second : 30.0;
    video->writer.open(video->partial_path.string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('H', '2', '6', '4'), fps,
                       video->size, {cv::VIDEOWRITER_PROP_IS_COLOR, 1});
    if (!video->writer.isOpened()) {
      videos_.erase(camera);
      throw std::runtime_error(fmt::format("cannot open an H.264 Matroska writer for '{}' (OpenCV's FFmpeg backend)",
                                           raw_video_name(camera)));
    }
  }
  if (rgb.size() != video->size) throw std::runtime_error(fmt::format("camera '{}' changed its image size", camera));
  cv::cvtColor(rgb, video->bgr, cv::COLOR_RGB2BGR);
  video->writer.write(video->bgr);
}

void SessionVideos::close() {
  for (auto& [camera, video] : videos_) {
    video->writer.release();
    std::filesystem::rename(video->partial_path, video->final_path);
  }
  videos_.clear();
}

void SessionVideos::discard() {
  for (auto& [camera, video] : videos_) {
    video->writer.release();
    std::error_code ignored;
    std::filesystem::remove(video->partial_path, ignored);
  }
  videos_.clear();
}

}  // namespace freeplay::recording
