#pragma once
// Planar geometry in the `sandtray` frame (metres, radians; x right, y up, on-screen y <= 0).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace freeplay {

/// A point or vector in the plane (metres).
using Vec2 = Eigen::Vector2d;
/// A simple polygon as an ordered list of vertices (not closed: the last vertex is not repeated).
using Polygon2 = std::vector<Vec2>;

/// A planar pose: position and heading θ (radians, counter-clockwise, θ = −screen rotation).
struct Pose2 {
  double x = 0.0;      ///< metres
  double y = 0.0;      ///< metres
  double theta = 0.0;  ///< radians

  /// The position as a vector.
  Vec2 position() const { return {x, y}; }
  /// Maps a point from this pose's local frame to the parent frame.
  Vec2 to_parent(const Vec2& local) const;
  /// Maps a point from the parent frame into this pose's local frame.
  Vec2 to_local(const Vec2& parent) const;
  /// The same pose as a 3-D isometry (z = 0, yaw = θ).
  Eigen::Isometry3d isometry() const;
};

/// True when `p` lies inside (or on the boundary of) `polygon` (even-odd rule).
bool point_in_polygon(const Polygon2& polygon, const Vec2& p);
/// Mean of the vertices (the centroid the real system uses for footprints and zones).
Vec2 vertex_mean(const Polygon2& polygon);
/// Signed area (positive for counter-clockwise vertex order).
double signed_area(const Polygon2& polygon);
/// Area-weighted centroid of a simple polygon (falls back to the vertex mean when degenerate).
Vec2 area_centroid(const Polygon2& polygon);
/// The polygon mapped from `pose`'s local frame to its parent frame.
Polygon2 transformed(const Polygon2& polygon, const Pose2& pose);
/// Euclidean distance from `p` to the polygon's boundary (0 on the boundary).
double distance_to_boundary(const Polygon2& polygon, const Vec2& p);
/// Signed distance: negative inside the polygon, positive outside.
double signed_distance(const Polygon2& polygon, const Vec2& p);
/// Axis-aligned bounds {min, max} of the vertices.
std::pair<Vec2, Vec2> bounds(const Polygon2& polygon);
/// Wraps an angle to (−π, π].
double wrap_angle(double radians);

}  // namespace freeplay
