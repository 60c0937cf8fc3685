#pragma once
// The session folder's raw camera videos, as the real dataset ships them: `video/camera_{purple,yellow,env}_raw.mkv`
// (Matroska, H.264 through Debian's OpenCV and FFmpeg), one frame per colour image the camera published.

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

namespace freeplay::recording {

/// The file name of `camera`'s raw video ("camera_purple" → camera_purple_raw.mkv, "env_camera" → camera_env_raw.mkv).
std::string raw_video_name(const std::string& camera);

/// Writes the colour frames of each camera to `<session>/video/<raw_video_name>` under a `…_raw.partial.mkv` name, renamed
/// when the session closes and deleted when it is discarded.
class SessionVideos {
 public:
  /// Videos in `session_dir`/video; `rates_hz` gives each camera's frame rate (a camera not listed: 30 Hz).
  SessionVideos(std::filesystem::path session_dir, std::map<std::string, double> rates_hz);
  ~SessionVideos();
  SessionVideos(const SessionVideos&) = delete;
  SessionVideos& operator=(const SessionVideos&) = delete;

  /// Appends one RGB frame (CV_8UC3, R, G, B; other images are skipped) of `camera`; opens its file at the first
  /// frame. Throws
  /// std::runtime_error when no H.264 Matroska writer can be opened.
  void write(const std::string& camera, const cv::Mat& rgb);
  /// Closes every video and gives it its final name.
  void close();
  /// Closes and deletes every video.
  void discard();

 private:
  struct Video;
  std::filesystem::path dir_;
  std::map<std::string, double> rates_hz_;
  std::map<std::string, std::unique_ptr<Video>> videos_;
};

}  // namespace freeplay::recording
