#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "freeplay/core/geometry.hpp"

using namespace freeplay;

TEST(Geometry, PointInPolygonSquare) {
  const Polygon2 square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_TRUE(point_in_polygon(square, {0.5, 0.5}));
  EXPECT_TRUE(point_in_polygon(square, {1.0, 0.5}));  // boundary counts
  EXPECT_FALSE(point_in_polygon(square, {1.5, 0.5}));
  EXPECT_NEAR(signed_area(square), 1.0, 1e-12);
  EXPECT_NEAR(signed_distance(square, {0.5, 0.5}), -0.5, 1e-12);
  EXPECT_NEAR(signed_distance(square, {2.0, 0.5}), 1.0, 1e-12);
}

TEST(Geometry, PointsWithinATrillionthOfAnEdgeCountAsInsideFromEverySide) {
  // Points that miss the crossing test but lie within 1e-12 of the boundary, on and just outside the vertices' box,
  // at small and large coordinates: inside, as the boundary test says; a little farther: outside.
  for (const double scale : {1.0, 1e4}) {
    const Polygon2 square = {{0, 0}, {scale, 0}, {scale, scale}, {0, scale}};
    for (const Vec2& edge_point : {Vec2(scale, 0.5 * scale), Vec2(0.0, 0.5 * scale), Vec2(0.5 * scale, scale),
                                   Vec2(0.5 * scale, 0.0), Vec2(scale, scale), Vec2(0.0, 0.0)}) {
      const Vec2 outward = (edge_point - Vec2(0.5 * scale, 0.5 * scale)).normalized();
      EXPECT_TRUE(point_in_polygon(square, edge_point)) << edge_point.transpose();
      EXPECT_TRUE(point_in_polygon(square, edge_point + 5e-13 * outward)) << edge_point.transpose();
      EXPECT_TRUE(std::signbit(signed_distance(square, edge_point + 5e-13 * outward))) << edge_point.transpose();
      EXPECT_FALSE(point_in_polygon(square, edge_point + 1e-9 * outward)) << edge_point.transpose();
      EXPECT_FALSE(point_in_polygon(square, edge_point + 0.25 * scale * outward)) << edge_point.transpose();
    }
  }
}

TEST(Geometry, PoseRoundTrip) {
  const Pose2 pose{0.2, -0.1, std::numbers::pi / 3};
  const Vec2 local(0.05, 0.01);
  const Vec2 world = pose.to_parent(local);
  EXPECT_TRUE(pose.to_local(world).isApprox(local, 1e-12));
  const Eigen::Vector3d via_iso = pose.isometry() * Eigen::Vector3d(local.x(), local.y(), 0.0);
  EXPECT_NEAR(via_iso.x(), world.x(), 1e-12);
  EXPECT_NEAR(via_iso.y(), world.y(), 1e-12);
}

TEST(Geometry, WrapAngle) {
  EXPECT_NEAR(wrap_angle(3 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(wrap_angle(-std::numbers::pi / 2 - 2 * std::numbers::pi), -std::numbers::pi / 2, 1e-12);
}

TEST(Geometry, CentroidsOfTriangle) {
  const Polygon2 tri = {{0, 0}, {3, 0}, {0, 3}};
  EXPECT_TRUE(vertex_mean(tri).isApprox(Vec2(1, 1)));
  EXPECT_TRUE(area_centroid(tri).isApprox(Vec2(1, 1)));
}

TEST(Geometry, WrapAngleKeepsAnglesInItsRangeAndShiftsOneTurnExactly) {
  // The sandtray's item poses skip wrap_angle's libm call on these ranges (sim/src/sandtray.cpp): same values.
  constexpr double kPi = std::numbers::pi;
  for (const double a : {std::nextafter(-kPi, 0.0), -1.0, 0.0, 2.5, kPi}) EXPECT_EQ(wrap_angle(a), a) << a;
  for (const double a : {std::nextafter(kPi, 4.0), 4.0, 7.5, std::nextafter(3 * kPi, 0.0)}) {
    EXPECT_EQ(wrap_angle(a), a - 2 * kPi) << a;
    EXPECT_EQ(wrap_angle(-a), -a + 2 * kPi) << a;
  }
}
