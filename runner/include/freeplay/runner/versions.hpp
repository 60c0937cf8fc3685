#pragma once
// Versions of the libraries a run used, recorded with every episode for reproducibility.

#include <nlohmann/json.hpp>

namespace freeplay::runner {

/// {"box2d": "2.4.1", "opencv": "4.6.0", "ompl": "1.5.2", "mujoco": "2.2.2", …} for the linked libraries.
nlohmann::json library_versions();

}  // namespace freeplay::runner
