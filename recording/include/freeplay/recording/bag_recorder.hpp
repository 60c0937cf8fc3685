#pragma once
// Records an episode like the real sandbox: a ROS 1 bag (`freeplay.bag`) with the real topics, types, frames and
// rates, plus `experiment.yaml` and the annotation YAML, in a PInSoRo-like session folder (docs/recording.md).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "freeplay/recording/record_settings.hpp"
#include "freeplay/recording/tick_topics.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::recording {

/// Files of one recorded session (`<run>/sessions/<episode id>/`).
struct SessionPaths {
  std::filesystem::path dir;          ///< the session folder
  std::filesystem::path bag;          ///< `freeplay.bag` (complete recordings)
  std::filesystem::path active_bag;   ///< `freeplay.bag.active` while recording (left behind by a kill)
  std::filesystem::path experiment;   ///< `experiment.yaml` (PInSoRo metadata)
  std::filesystem::path annotations;  ///< `freeplay.annotations.freeplay-sim.yaml` (ground truth, bag time base)
  std::filesystem::path bag_yaml;     ///< `freeplay.bag.yaml` (rosbag info --yaml of the closed bag)
};
/// The files of the session folder `dir`.
inline SessionPaths session_paths(const std::filesystem::path& dir) {
  return {dir, dir / "freeplay.bag", dir / "freeplay.bag.active", dir / "experiment.yaml",
          dir / "freeplay.annotations.freeplay-sim.yaml", dir / "freeplay.bag.yaml"};
}

/// The recorder's own topics (the tick's real topics are in tick_topics.hpp; the camera topics in camera_topics()).
namespace topics {
inline constexpr const char* kAllSpeech = "/freeplay/speech";                       ///< String: JSON, everyone's
inline constexpr const char* kEvents = "/freeplay/events";                          ///< String: JSON, the event log
inline constexpr const char* kAnnotations = "/freeplay/annotations";                ///< String: PInSoRo YAML
inline constexpr const char* kScenario = "/freeplay/scenario";  ///< String, latched: the validated scenario YAML
inline constexpr const char* kEpisode = "/freeplay/episode";    ///< String, latched: JSON {id, seed, scenario}
}  // namespace topics

/// Counts of what a recorder wrote.
struct RecordingStats {
  std::uint64_t messages = 0;  ///< messages written
  std::uint64_t frames = 0;    ///< camera frames written (colour and depth count once per FramePack)
  std::uint64_t events = 0;    ///< event-log entries written to /freeplay/events
};

/// Writes one episode's session folder; an EpisodeObserver (the simulation) and a FrameSink (the cameras).
/// Not copyable; `write` may be called from another thread than the observer calls.
class BagRecorder final : public runner::EpisodeObserver, public runner::FrameSink {
 public:
  /// A recorder writing `sessions_root/<episode id>/` with `settings`.
  explicit BagRecorder(std::filesystem::path sessions_root, RecordSettings settings = {});
  /// Closes an open bag as `abort` does.
  ~BagRecorder() override;
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  /// Creates the session folder, opens `freeplay.bag.active` and writes the scenario and episode identity (latched);
  /// InputError when the folder is not writable.
  void begin(const runner::EpisodeInfo& info) override;
  /// Writes the tick's /tf (with the Nao's links in child-robot episodes), joint states, poses, background, zones,
  /// footprints and events.
  void observe(const runner::EpisodeSnapshot& snapshot) override;
  /// Writes the annotations, closes the bag, renames it `freeplay.bag`, writes experiment.yaml and the annotation
  /// YAML, and adds `recording` (the session folder, relative to the run folder) to the record.
  void end(runner::EpisodeResult& result) override;
  /// Closes the bag (readable, indexed), renames it and marks experiment.yaml incomplete (`issues:`).
  void abort() override;
  /// Writes one camera frame (JPEG colour, compressedDepth depth, camera_info, optical frame on /tf).
  void write(const stage::FramePack& frame) override;
  /// Notes the renderer in experiment.yaml.
  void set_gl_renderer(const std::string& renderer) override;

  /// The session folder (valid after begin).
  const SessionPaths& paths() const;
  /// What has been written so far.
  RecordingStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace freeplay::recording
