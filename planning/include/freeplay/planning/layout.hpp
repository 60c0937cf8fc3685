#pragma once
// Random tray layouts (items scattered on the play area) for benchmarks, tests and the CLI.

#include <string>
#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/planning/plan.hpp"

namespace freeplay::planning {

/// An item's outline in its own frame (origin = item centre).
struct ItemShape {
  std::string name;  ///< item name, e.g. "zebra"
  Polygon2 polygon;  ///< vertices in the item frame (metres)
};

/// An item placed on the tray.
struct PlacedItem {
  std::string name;   ///< item name
  Pose2 pose;         ///< item centre and heading in `sandtray`
  Polygon2 footprint; ///< outline in `sandtray`
};

/// A set of placed items.
struct Layout {
  std::vector<PlacedItem> items;  ///< placed items, in placement order
  /// The items as planner obstacles.
  std::vector<Obstacle> obstacles() const;
};

/// Where and how densely `random_layout` places items.
struct LayoutOptions {
  Vec2 area_min{0.0, -0.335};   ///< lower-left corner of the play area (sandtray frame)
  Vec2 area_max{0.528, 0.0};    ///< upper-right corner (x < 0.528 m keeps items out of the stash)
  double min_gap_m = 0.005;     ///< least distance between two footprints
  int max_attempts_per_item = 2000;  ///< rejection-sampling attempts before giving up
};

/// Approximate outlines of the ten free-play items from the logged footprint extents (reference §3.3):
/// hexagons fitted in the extents, octagons for ball/boy/girl. A stand-in until the sim catalogue is used.
std::vector<ItemShape> approximate_item_shapes();

/// Places `n_items` distinct shapes (chosen at random) at random poses, fully inside the play area and at least
/// `min_gap_m` apart; throws InputError when n_items is out of range or the items do not fit.
Layout random_layout(const std::vector<ItemShape>& shapes, int n_items, Rng& rng, const LayoutOptions& options = {});

/// Least distance between two polygons (0 when they touch or overlap).
double polygon_distance(const Polygon2& a, const Polygon2& b);
/// True when the two polygons' areas or boundaries intersect.
bool polygons_intersect(const Polygon2& a, const Polygon2& b);

}  // namespace freeplay::planning
