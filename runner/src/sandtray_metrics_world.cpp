// The live sandtray as the metrics' world (apart from results/src/episode_metrics.cpp, which links no simulation).
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/zones.hpp"
#include "sim_world.hpp"

namespace freeplay::runner::detail {

Vec2 SandtrayMetricsWorld::item_position(const std::string& item) const { return tray_.item(item).pose.position(); }

std::string SandtrayMetricsWorld::zone_at(const Vec2& p) const {
  const auto* zone = tray_.zones().at(p);
  return zone != nullptr ? zone->colour : "";
}

}  // namespace freeplay::runner::detail
