// `freeplay list items [--json]`: the item catalogue with sizes, footprint extents and physics.

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "freeplay/core/geometry.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::cli {
namespace {

void print_items(bool json) {
  const auto catalogue = sim::ItemCatalogue::load_default();
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& spec : catalogue.items()) {
      const auto [lo, hi] = bounds(spec.polygon);
      nlohmann::json polygon = nlohmann::json::array();
      for (const auto& v : spec.polygon) polygon.push_back({v.x(), v.y()});
      out.push_back({{"name", spec.name},
                     {"label", spec.label},
                     {"scale", spec.scale},
                     {"box_side_m", spec.box_side_m},
                     {"polygon", polygon},
                     {"footprint_extent_m", {{"x", {lo.x(), hi.x()}}, {"y", {lo.y(), hi.y()}}}},
                     {"area_m2", signed_area(spec.polygon)},
                     {"physics",
                      {{"density", spec.density}, {"friction", spec.friction}, {"restitution", spec.restitution}}},
                     {"picture", spec.picture},
                     {"colour", spec.colour}});
    }
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::cout << fmt::format("{:<10} {:>5} {:>7} {:>4}  {:<19} {:<19} {:>8} {:>4} {:>4} {:>4}\n", "item", "scale",
                           "box cm", "vert", "footprint x (cm)", "footprint y (cm)", "area cm2", "dens", "fric", "rest");
  for (const auto& spec : catalogue.items()) {
    const auto [lo, hi] = bounds(spec.polygon);
    std::cout << fmt::format("{:<10} {:>5.2f} {:>7.2f} {:>4}  [{:>6.2f}, {:>6.2f}]    [{:>6.2f}, {:>6.2f}]    "
                             "{:>8.1f} {:>4.1f} {:>4.1f} {:>4.1f}\n",
                             spec.name, spec.scale, spec.box_side_m * 100.0, spec.polygon.size(), lo.x() * 100.0,
                             hi.x() * 100.0, lo.y() * 100.0, hi.y() * 100.0, signed_area(spec.polygon) * 1e4,
                             spec.density, spec.friction, spec.restitution);
  }
  std::cout << fmt::format("\nBox2D world: 1 unit = {:.0f} mm (the real game's 32 px at 1920 px), zero gravity, "
                           "damping 5, mouse joints 5 Hz / ζ 1 / max force 500 × mass.\n",
                           1000.0 / sim::kPhysicsUnitsPerMetre);
}

const RegisterLister kListItems("items", "Interactive items: sizes, footprint extents and physics", print_items);

}  // namespace
}  // namespace freeplay::cli
