#pragma once
// Records an episode like the real sandbox: a ROS 1 bag (`freeplay.bag`) with the real topics, types, frames and
// rates, plus `experiment.yaml` and the annotation YAML, in a PInSoRo-like session folder (docs/recording.md).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "freeplay/recording/record_settings.hpp"
#include "freeplay/recording/session_layout.hpp"
#include "freeplay/recording/tick_topics.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::recording {

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
