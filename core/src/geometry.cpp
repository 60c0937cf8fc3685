#include "freeplay/core/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace freeplay {

Vec2 Pose2::to_parent(const Vec2& local) const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {x + c * local.x() - s * local.y(), y + s * local.x() + c * local.y()};
}

Vec2 Pose2::to_local(const Vec2& parent) const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  const double dx = parent.x() - x;
  const double dy = parent.y() - y;
  return {c * dx + s * dy, -s * dx + c * dy};
}

Eigen::Isometry3d Pose2::isometry() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, y, 0.0);
  t.linear() = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

namespace {

// The even-odd crossing test of `p` against the polygon's edges (boundary points may fall either way), and the
// bounding box of its vertices.
bool crosses_odd_times(const Polygon2& polygon, const Vec2& p, Vec2& lo, Vec2& hi) {
  lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    lo = lo.cwiseMin(a);
    hi = hi.cwiseMax(a);
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x();
      if (p.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

// True when `p` lies so far outside the box [lo, hi] that its distance to any edge inside the box, rounding
// included, exceeds the 1e-12 m within which a boundary point counts as inside.
bool clear_of_box(const Vec2& p, const Vec2& lo, const Vec2& hi) {
  const double scale = std::max({1.0, p.cwiseAbs().maxCoeff(), lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()});
  const double margin = 1e-6 * scale;
  return (p.array() < lo.array() - margin).any() || (p.array() > hi.array() + margin).any();
}

}  // namespace

bool point_in_polygon(const Polygon2& polygon, const Vec2& p) {
  if (polygon.size() < 3) return false;
  Vec2 lo, hi;
  if (crosses_odd_times(polygon, p, lo, hi)) return true;
  return !clear_of_box(p, lo, hi) && distance_to_boundary(polygon, p) < 1e-12;
}

Vec2 vertex_mean(const Polygon2& polygon) {
  Vec2 sum = Vec2::Zero();
  for (const auto& v : polygon) sum += v;
  return polygon.empty() ? sum : Vec2(sum / static_cast<double>(polygon.size()));
}

double signed_area(const Polygon2& polygon) {
  double twice = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    twice += polygon[j].x() * polygon[i].y() - polygon[i].x() * polygon[j].y();
  }
  return 0.5 * twice;
}

Vec2 area_centroid(const Polygon2& polygon) {
  const double area = signed_area(polygon);
  if (std::abs(area) < 1e-15) return vertex_mean(polygon);
  Vec2 c = Vec2::Zero();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double cross = polygon[j].x() * polygon[i].y() - polygon[i].x() * polygon[j].y();
    c += (polygon[j] + polygon[i]) * cross;
  }
  return c / (6.0 * area);
}

Polygon2 transformed(const Polygon2& polygon, const Pose2& pose) {
  Polygon2 out;
  out.reserve(polygon.size());
  for (const auto& v : polygon) out.push_back(pose.to_parent(v));
  return out;
}

double distance_to_boundary(const Polygon2& polygon, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 a = polygon[j];
    const Vec2 ab = polygon[i] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

double signed_distance(const Polygon2& polygon, const Vec2& p) {
  const double d = distance_to_boundary(polygon, p);
  Vec2 lo, hi;
  const bool inside = polygon.size() >= 3 && (crosses_odd_times(polygon, p, lo, hi) || d < 1e-12);
  return inside ? -d : d;
}

std::pair<Vec2, Vec2> bounds(const Polygon2& polygon) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  for (const auto& v : polygon) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return {lo, hi};
}

double wrap_angle(double radians) {
  double a = std::remainder(radians, 2.0 * std::numbers::pi);
  if (a <= -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

}  // namespace freeplay
