#pragma once
// The names scenario files may use, collected from the registries of the linked libraries.

#include "freeplay/scenario/scenario.hpp"

namespace freeplay::cli {

/// Policies, planners, cameras and audio voices known to this build.
scenario::ScenarioVocabulary scenario_vocabulary();

/// The scenarios folder shipped with the program (`scenarios/` of the source tree, or $FREEPLAY_SCENARIOS_DIR).
std::filesystem::path scenarios_dir();

}  // namespace freeplay::cli
