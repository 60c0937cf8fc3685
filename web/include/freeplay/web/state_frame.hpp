#pragma once
// The JSON a page sees of a running episode (schema: docs/web.md): the static scene (screen, items' footprints)
// once, then a state frame at every 10 Hz tick built from the episode's snapshot.

#include <nlohmann/json.hpp>
#include <string>

#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::sim {
class Sandtray;
class ItemCatalogue;
}  // namespace freeplay::sim

namespace freeplay::web {

/// The static scene: screen size (m and px), each item's footprint polygon (item frame), label and colour, the
/// scenario's condition, seats, protocol durations and free-play cap.
nlohmann::json scene_json(const sim::ItemCatalogue& catalogue, const scenario::Scenario& scenario);

/// The ground truth of one tick: clock, stage, items, touches, children, robot body (without the wizard's state,
/// the zones and the events, which the session adds).
nlohmann::json tick_json(const runner::EpisodeSnapshot& snapshot);

/// The colour zones of the current background: [{colour, id, centroid, polygon}].
nlohmann::json zones_json(const sim::Sandtray& tray);

}  // namespace freeplay::web
