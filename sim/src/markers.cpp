#include "freeplay/sim/markers.hpp"

#include "freeplay/sim/zones.hpp"

namespace freeplay::sim {

namespace {

LineMarker closed(const Polygon2& polygon) {
  LineMarker line;
  for (const auto& v : polygon) line.points.push_back({v.x(), v.y()});
  if (!polygon.empty()) line.points.push_back({polygon.front().x(), polygon.front().y()});
  return line;
}

}  // namespace

std::vector<LineMarker> footprint_markers(const Sandtray& tray) {
  std::vector<LineMarker> out;
  int id = 0;
  for (const auto& [name, polygon] : tray.published_footprints()) {
    auto line = closed(polygon);
    line.frame = "/" + name;
    line.ns = name;
    line.id = id++;
    out.push_back(std::move(line));
  }
  return out;
}

std::vector<LineMarker> zone_markers(const Sandtray& tray) {
  std::vector<LineMarker> out;
  for (const auto& zone : tray.zones().zones()) {
    auto line = closed(zone.polygon);
    line.frame = "/sandtray";
    line.ns = "sandbox_zone_" + zone.colour;
    line.id = zone.id;
    const auto rgb = zone_marker_rgb(zone.colour);
    line.rgb = {static_cast<float>(rgb[0]) / 255.F, static_cast<float>(rgb[1]) / 255.F,
                static_cast<float>(rgb[2]) / 255.F};
    line.width = 0.005;
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace freeplay::sim
