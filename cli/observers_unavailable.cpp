// `freeplay-run`'s observers: none. It links neither the recorder nor the camera rig's renderer and video encoders;
// `run_command` hands a run that needs them to `freeplay-full` before it starts (cli/episode_observers.hpp).
#include "episode_observers.hpp"

namespace freeplay::cli {

bool observers_available() { return false; }

runner::ObserverFactory make_observer_factory(ObserverOptions /*options*/) {
  return [](const scenario::Scenario& /*scenario*/, const std::filesystem::path& /*run_dir*/) {
    return runner::EpisodeObservers{};
  };
}

}  // namespace freeplay::cli
