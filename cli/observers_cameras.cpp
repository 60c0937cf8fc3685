// Placeholder until the camera rig lands: no episode renders.
#include "episode_observers.hpp"

namespace freeplay::cli {

void add_camera_observers(const runner::Scenario&, const std::filesystem::path&, const ObserverOptions&,
                          runner::EpisodeObservers&, const std::vector<runner::FrameSink*>&) {}

}  // namespace freeplay::cli
