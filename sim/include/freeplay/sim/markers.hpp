#pragma once
// The game's line markers as plain data: `/footprints` (the game's FootprintsPublisher) and `/zones`
// (zones_from_image). One home for their frames, namespaces, ids, colours and widths: the live graph
// (`freeplay serve`) and the bag recorder both build their visualization_msgs/Marker from these.

#include <array>
#include <string>
#include <vector>

#include "freeplay/sim/sandtray.hpp"

namespace freeplay::sim {

/// A closed LINE_STRIP marker (the first point repeated at the end).
struct LineMarker {
  std::string frame;                          ///< header.frame_id ("/hippo", "/sandtray")
  std::string ns;                             ///< marker namespace ("hippo", "sandbox_zone_blue")
  int id = 0;                                 ///< marker id
  std::vector<std::array<double, 2>> points;  ///< x, y (m)
  std::array<float, 3> rgb{0.F, 1.F, 0.F};    ///< colour (0–1), alpha 1
  double width = 0.002;                       ///< scale.x (m)
};

/// `/footprints`: one green polygon per item in the item's own frame ("/<item>", ns = item, ids 0, 1, …).
std::vector<LineMarker> footprint_markers(const Sandtray& tray);
/// `/zones` after its DELETEALL: one polygon per zone in "/sandtray", ns `sandbox_zone_<colour>`, 5 mm wide.
std::vector<LineMarker> zone_markers(const Sandtray& tray);

}  // namespace freeplay::sim
