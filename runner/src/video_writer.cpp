#include "freeplay/runner/video_writer.hpp"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>
#include <system_error>

#include "freeplay/runner/episode.hpp"

namespace freeplay::runner {

std::filesystem::path video_relative_path(const std::string& episode_id, const std::string& camera) {
  return std::filesystem::path("videos") / episode_id / (camera + ".mp4");
}

/// One camera's video being written.
struct VideoFileSink::Video {
  std::filesystem::path final_path;
  std::filesystem::path partial_path;
  cv::VideoWriter writer;
  cv::Size size;
  cv::Mat bgr;
};

VideoFileSink::VideoFileSink(const scenario::Scenario& scenario, std::filesystem::path run_dir) : run_dir_(std::move(run_dir)) {
  for (const auto& camera : scenario.cameras) {
    if (camera.video) rates_[camera.name] = camera.rate_hz;
  }
}

VideoFileSink::~VideoFileSink() { abort(); }

void VideoFileSink::begin(const EpisodeInfo& info) {
  close_all();
  episode_id_ = info.id;
}

void VideoFileSink::observe(const EpisodeSnapshot& /*snapshot*/) {}

void VideoFileSink::write(const stage::FramePack& frame) {
  const auto rate = rates_.find(frame.camera);
  if (rate == rates_.end() || frame.rgb.empty()) return;
  auto& video = videos_[frame.camera];
  if (video == nullptr) {
    video = std::make_unique<Video>();
    video->final_path = run_dir_ / video_relative_path(episode_id_, frame.camera);
    video->partial_path = video->final_path;
    video->partial_path.replace_filename(frame.camera + ".partial.mp4");  // the extension picks the container
    std::filesystem::create_directories(video->final_path.parent_path());
    video->size = frame.rgb.size();
    if (!video->writer.open(video->partial_path.string(), cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'),
                            rate->second, video->size)) {
      const auto path = video->partial_path;
      videos_.erase(frame.camera);
      throw std::runtime_error(fmt::format("cannot write the video {} (OpenCV's FFmpeg backend, fourcc mp4v)",
                                           path.string()));
    }
  }
  if (frame.rgb.size() != video->size) {
    throw std::runtime_error(fmt::format("camera {}: frame size {}x{} differs from the video's {}x{}", frame.camera,
                                         frame.rgb.cols, frame.rgb.rows, video->size.width, video->size.height));
  }
  cv::cvtColor(frame.rgb, video->bgr, cv::COLOR_RGB2BGR);
  video->writer.write(video->bgr);
}

void VideoFileSink::end(EpisodeResult& result) {
  for (auto& [camera, video] : videos_) {
    video->writer.release();
    std::filesystem::rename(video->partial_path, video->final_path);
    result.record["cameras"]["videos"][camera] = video_relative_path(episode_id_, camera).generic_string();
  }
  videos_.clear();
}

void VideoFileSink::abort() { close_all(); }

void VideoFileSink::close_all() {
  for (auto& [camera, video] : videos_) {
    video->writer.release();
    std::error_code ignored;
    std::filesystem::remove(video->partial_path, ignored);
  }
  videos_.clear();
}

}  // namespace freeplay::runner
