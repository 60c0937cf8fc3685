#pragma once
// What watches each episode of `freeplay run/suite`: the ROS bag recorder (with `record:` or `--record`) and the
// camera rig (when the scenario lists cameras), which hands its frames to the recorder and the video writers.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/frame_sink.hpp"

namespace freeplay::cli {

/// Command-line choices that shape the observers.
struct ObserverOptions {
  bool record = false;  ///< `--record`: record every episode even when its scenario does not ask for it
};

/// Whether the episodes of `scenario` are watched at all: recorded, or filmed into videos (cameras whose frames
/// nothing consumes are not rendered).
inline bool has_observers(const scenario::Scenario& scenario, const ObserverOptions& options) {
  return scenario.record || options.record ||
         std::any_of(scenario.cameras.begin(), scenario.cameras.end(), [](const auto& c) { return c.video; });
}

/// Whether this executable can record and render (`freeplay-full`); `freeplay-run` hands such runs over to it.
bool observers_available();

/// The observer factory of `freeplay run/suite`: recorder first (it is also a frame sink), then the camera rig.
runner::ObserverFactory make_observer_factory(ObserverOptions options);

/// Adds the recorder of one episode when it records; pushes the frame sinks it wants fed (cli/observers_recording.cpp).
void add_recording_observers(const scenario::Scenario& scenario, const std::filesystem::path& run_dir,
                             const ObserverOptions& options, runner::EpisodeObservers& observers,
                             std::vector<runner::FrameSink*>& frame_sinks);

/// Adds the camera rig when the scenario lists cameras, feeding `frame_sinks` and its own video writers
/// (cli/observers_cameras.cpp).
void add_camera_observers(const scenario::Scenario& scenario, const std::filesystem::path& run_dir,
                          const ObserverOptions& options, runner::EpisodeObservers& observers,
                          const std::vector<runner::FrameSink*>& frame_sinks);

}  // namespace freeplay::cli
