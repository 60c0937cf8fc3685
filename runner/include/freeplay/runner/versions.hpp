#pragma once
// Versions of the libraries a run used, recorded with every episode for reproducibility.

#include <nlohmann/json.hpp>

#include "freeplay/core/event_log.hpp"

namespace freeplay::runner {

/// {"box2d": "2.4.1", "opencv": "4.6.0", "ompl": "1.5.2", "mujoco": "2.2.2", …} for the linked libraries.
nlohmann::json library_versions();

/// The record fields every kind of episode writes about its event log and build: `events`, `event_log_hash`,
/// `gl_renderer` (null; the camera rig fills it in) and `libraries`.
nlohmann::json provenance_fields(const EventLog& log);

}  // namespace freeplay::runner
