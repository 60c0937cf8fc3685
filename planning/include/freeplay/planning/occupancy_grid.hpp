#pragma once
// The occupancy map of the real planner (`sandbox_map_and_plan`): 5 mm cells, blurred footprints, 0–100.

#include <string_view>
#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/planning/plan.hpp"

namespace freeplay::planning {

/// A grid cell: column (x / 5 mm) and row (−y / 5 mm, row 0 at the top edge y = 0).
struct Cell {
  int col = 0;  ///< x index
  int row = 0;  ///< −y index
  /// Component-wise equality.
  friend bool operator==(const Cell&, const Cell&) = default;
};

/// Immutable 120 × 67 occupancy grid over the screen, built from the other items' footprints.
class OccupancyGrid {
 public:
  static constexpr double kResolutionM = 0.005;  ///< cell side (real `RESOLUTION`)
  static constexpr double kWidthM = 0.600;       ///< map width
  static constexpr double kHeightM = 0.335;      ///< map height
  static constexpr int kCols = 120;              ///< cells along x
  static constexpr int kRows = 67;               ///< cells along −y
  static constexpr int kFree = 0;                ///< occupancy of a free cell
  static constexpr int kOccupied = 100;          ///< occupancy of a fully covered cell
  static constexpr double kOutsideCostPerCell = 10.0;  ///< A* cost per cell of distance outside the map

  /// All free.
  OccupancyGrid();
  /// Rasterises every footprint except `inhibited`'s (filled convex polygon), 3 × 3 box blur, 100 − v·100/255.
  static OccupancyGrid build(const std::vector<Obstacle>& obstacles, std::string_view inhibited);

  /// The cell containing `p` (floor of x / 5 mm and −y / 5 mm; may lie outside the map).
  static Cell cell_of(const Vec2& p);
  /// The path point of a cell as the real planner emits it: (col · 5 mm, −row · 5 mm).
  static Vec2 cell_point(const Cell& c);
  /// True when the cell lies on the map.
  static bool contains(const Cell& c) { return c.col >= 0 && c.col < kCols && c.row >= 0 && c.row < kRows; }
  /// The map cell nearest to `c` (itself when on the map).
  static Cell clamp(const Cell& c);

  /// Occupancy 0…100 of a map cell (row 0 = top edge; the real code's one-row offset is fixed).
  int occupancy(const Cell& c) const { return occupancy_[index(c)]; }
  /// Occupancy of the nearest map cell (used for cells outside the map).
  int occupancy_clamped(const Cell& c) const { return occupancy(clamp(c)); }
  /// A* cost of entering `c`: occupancy + 1 on the map; outside, nearest edge cell cost + 10 × distance in cells.
  double step_cost(const Cell& c) const { return contains(c) ? occupancy(c) + 1.0 : outside_step_cost(c); }
  /// Sets one map cell's occupancy (for tests and hand-made maps).
  void set_occupancy(const Cell& c, int value);

 private:
  double outside_step_cost(const Cell& c) const;
  static std::size_t index(const Cell& c) {
    return static_cast<std::size_t>(c.row) * kCols + static_cast<std::size_t>(c.col);
  }
  std::vector<int> occupancy_;
};

}  // namespace freeplay::planning
