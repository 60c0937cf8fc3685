// The recorder of `freeplay run/suite`: a BagRecorder per episode when the scenario has `record:` or with --record.
#include "episode_observers.hpp"

#ifdef FREEPLAY_WITH_RECORDING
#include "freeplay/recording/bag_recorder.hpp"
#else
#include "freeplay/core/error.hpp"
#endif

namespace freeplay::cli {

void add_recording_observers(const scenario::Scenario& scenario, const std::filesystem::path& run_dir,
                             const ObserverOptions& options, runner::EpisodeObservers& observers,
                             std::vector<runner::FrameSink*>& frame_sinks) {
  if (!scenario.record && !options.record) return;
#ifdef FREEPLAY_WITH_RECORDING
  auto recorder = std::make_unique<recording::BagRecorder>(run_dir / "sessions", scenario.recording);
  frame_sinks.push_back(recorder.get());
  observers.push_back(std::move(recorder));
#else
  (void)run_dir, (void)observers, (void)frame_sinks;
  throw InputError("this freeplay was built without the ROS 1 bag libraries", "record",
                   "record: false (or install them with scripts/setup.sh and rebuild)");
#endif
}

}  // namespace freeplay::cli
