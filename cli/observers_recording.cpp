// Placeholder until the recorder lands: no episode records.
#include "episode_observers.hpp"

namespace freeplay::cli {

void add_recording_observers(const runner::Scenario&, const std::filesystem::path&, const ObserverOptions&,
                             runner::EpisodeObservers&, std::vector<runner::FrameSink*>&) {}

}  // namespace freeplay::cli
