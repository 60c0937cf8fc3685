#pragma once
// Camera videos of an episode: one MP4 (MPEG-4 Part 2, fourcc mp4v, fps = the camera's rate) per camera under
// `<run_dir>/videos/<episode id>/<camera>.mp4`, written under a temporary name and renamed when the episode ends.

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::runner {

/// Where a camera's video of an episode goes, relative to the run folder.
std::filesystem::path video_relative_path(const std::string& episode_id, const std::string& camera);

/// Writes the colour frames of the scenario cameras with `video: true` to MP4 files; an observer too, so that
/// the files appear (renamed atomically) when the episode ends and vanish when it aborts.
class VideoFileSink final : public FrameSink, public EpisodeObserver {
 public:
  /// Videos of the `video: true` cameras of `scenario`, under `run_dir`.
  VideoFileSink(const scenario::Scenario& scenario, std::filesystem::path run_dir);
  ~VideoFileSink() override;
  VideoFileSink(const VideoFileSink&) = delete;
  VideoFileSink& operator=(const VideoFileSink&) = delete;

  /// Remembers the episode id (the folder of its videos).
  void begin(const EpisodeInfo& info) override;
  /// Nothing: frames arrive through `write`.
  void observe(const EpisodeSnapshot& snapshot) override;
  /// Closes and renames the videos; adds `cameras.videos` {camera: path relative to the run folder}.
  void end(EpisodeResult& result) override;
  /// Closes and deletes the partial videos.
  void abort() override;

  /// Appends a frame of a video camera (RGB → BGR); opens its file at the first frame; ignores other cameras.
  void write(const stage::FramePack& frame) override;

  /// True for the cameras this sink writes.
  bool wants(const std::string& camera) const { return rates_.count(camera) != 0; }

 private:
  struct Video;
  void close_all();

  std::filesystem::path run_dir_;
  std::string episode_id_;
  std::map<std::string, double> rates_;
  std::map<std::string, std::unique_ptr<Video>> videos_;
};

}  // namespace freeplay::runner
