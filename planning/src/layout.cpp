#include "freeplay/planning/layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include <fmt/format.h>

#include "freeplay/core/error.hpp"

namespace freeplay::planning {

namespace {

// Hexagon fitted in the extents [x0, x1] × [y0, y1] (counter-clockwise).
Polygon2 hexagon(double x0, double x1, double y0, double y1) {
  const double quarter = (x1 - x0) / 4.0;
  const double mid = (y0 + y1) / 2.0;
  return {{x0, mid}, {x0 + quarter, y0}, {x1 - quarter, y0}, {x1, mid}, {x1 - quarter, y1}, {x0 + quarter, y1}};
}

// Regular octagon of circumradius r (the game's default bounding polygon).
Polygon2 octagon(double r) {
  Polygon2 out;
  for (int k = 0; k < 8; ++k) {
    const double a = (k + 0.5) * std::numbers::pi / 4.0;
    out.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return out;
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

bool segments_intersect(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const double d1 = cross(q2 - q1, p1 - q1);
  const double d2 = cross(q2 - q1, p2 - q1);
  const double d3 = cross(p2 - p1, q1 - p1);
  const double d4 = cross(p2 - p1, q2 - p1);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

double radius(const Polygon2& polygon) {
  double r = 0.0;
  for (const auto& v : polygon) r = std::max(r, v.norm());
  return r;
}

}  // namespace

std::vector<Obstacle> Layout::obstacles() const {
  std::vector<Obstacle> out;
  out.reserve(items.size());
  for (const auto& item : items) out.push_back({item.name, item.footprint});
  return out;
}

std::vector<ItemShape> approximate_item_shapes() {
  return {
      {"zebra", hexagon(-0.0169, 0.0132, -0.0157, 0.0168)},
      {"elephant", hexagon(-0.0258, 0.0234, -0.0158, 0.0170)},
      {"giraffe", hexagon(-0.0174, 0.0136, -0.0226, 0.0276)},
      {"hippo", hexagon(-0.0239, 0.0257, -0.0142, 0.0167)},
      {"lion", hexagon(-0.0124, 0.0156, -0.0181, 0.0147)},
      {"crocodile", hexagon(-0.0137, 0.0172, -0.0155, 0.0174)},
      {"caravan", hexagon(-0.0400, 0.0435, -0.0120, 0.0175)},
      {"ball", octagon(0.0118)},
      {"boy", octagon(0.0169)},
      {"girl", octagon(0.0169)},
  };
}

bool polygons_intersect(const Polygon2& a, const Polygon2& b) {
  if (a.empty() || b.empty()) return false;
  if (point_in_polygon(b, a.front()) || point_in_polygon(a, b.front())) return true;
  for (std::size_t i = 0, j = a.size() - 1; i < a.size(); j = i++) {
    for (std::size_t k = 0, l = b.size() - 1; k < b.size(); l = k++) {
      if (segments_intersect(a[j], a[i], b[l], b[k])) return true;
    }
  }
  return false;
}

double polygon_distance(const Polygon2& a, const Polygon2& b) {
  if (polygons_intersect(a, b)) return 0.0;
  double d = std::numeric_limits<double>::infinity();
  for (const auto& v : a) d = std::min(d, distance_to_boundary(b, v));
  for (const auto& v : b) d = std::min(d, distance_to_boundary(a, v));
  return d;
}

Layout random_layout(const std::vector<ItemShape>& shapes, int n_items, Rng& rng, const LayoutOptions& options) {
  if (n_items < 0 || static_cast<std::size_t>(n_items) > shapes.size()) {
    throw InputError(fmt::format("cannot place {} items from {} shapes", n_items, shapes.size()), "n_items",
                     fmt::format("0 … {}", shapes.size()));
  }
  std::vector<std::size_t> order(shapes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  rng.shuffle(order);

  Layout layout;
  for (int n = 0; n < n_items; ++n) {
    const ItemShape& shape = shapes[order[static_cast<std::size_t>(n)]];
    const double r = radius(shape.polygon);
    const Vec2 lo = options.area_min + Vec2(r, r);
    const Vec2 hi = options.area_max - Vec2(r, r);
    if (lo.x() >= hi.x() || lo.y() >= hi.y()) {
      throw InputError(fmt::format("item '{}' does not fit in the play area", shape.name), "area");
    }
    bool placed = false;
    for (int attempt = 0; attempt < options.max_attempts_per_item && !placed; ++attempt) {
      Pose2 pose;
      pose.x = rng.uniform(lo.x(), hi.x());
      pose.y = rng.uniform(lo.y(), hi.y());
      pose.theta = rng.uniform(-std::numbers::pi, std::numbers::pi);
      Polygon2 footprint = transformed(shape.polygon, pose);
      const bool clear = std::none_of(layout.items.begin(), layout.items.end(), [&](const PlacedItem& other) {
        return polygon_distance(footprint, other.footprint) < options.min_gap_m;
      });
      if (clear) {
        layout.items.push_back({shape.name, pose, std::move(footprint)});
        placed = true;
      }
    }
    if (!placed) {
      throw InputError(fmt::format("could not place '{}' after {} attempts", shape.name,
                                   options.max_attempts_per_item),
                       "n_items", "fewer items or a smaller gap");
    }
  }
  return layout;
}

}  // namespace freeplay::planning
