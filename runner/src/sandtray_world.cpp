#include "freeplay/runner/sandtray_world.hpp"

#include <algorithm>

#include "freeplay/sim/item_catalogue.hpp"

namespace freeplay::runner {

planning::MoveWorld sandtray_move_world(const sim::Sandtray& tray) {
  planning::MoveWorld world;
  world.item_centre = [&tray](const std::string& name) -> std::optional<Vec2> {
    if (tray.catalogue().find(name) == nullptr) return std::nullopt;
    return tray.item(name).pose.position();
  };
  world.footprints = [&tray] {
    const auto items = tray.items();
    std::vector<planning::Obstacle> out;
    for (const auto& [name, polygon] : tray.published_footprints()) {
      for (const auto& item : items) {
        if (item.name == name) out.push_back({name, transformed(polygon, item.pose)});
      }
    }
    return out;
  };
  world.held_by_child = [&tray](const std::string& name) {
    const auto holders = tray.item(name).holders;
    return std::any_of(holders.begin(), holders.end(),
                       [](const sim::Holder& h) { return h.kind == sim::Holder::Kind::Finger; });
  };
  return world;
}

}  // namespace freeplay::runner
