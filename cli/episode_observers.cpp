#include "episode_observers.hpp"

namespace freeplay::cli {

bool observers_available() { return true; }

runner::ObserverFactory make_observer_factory(ObserverOptions options) {
  return [options](const scenario::Scenario& scenario, const std::filesystem::path& run_dir) {
    runner::EpisodeObservers observers;
    if (!has_observers(scenario, options)) return observers;
    std::vector<runner::FrameSink*> frame_sinks;
    add_recording_observers(scenario, run_dir, options, observers, frame_sinks);
    add_camera_observers(scenario, run_dir, options, observers, frame_sinks);
    return observers;
  };
}

}  // namespace freeplay::cli
