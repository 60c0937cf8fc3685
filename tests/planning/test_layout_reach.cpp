// Random tray layouts and the arm-reach disc.

#include <gtest/gtest.h>

#include <set>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/layout.hpp"
#include "freeplay/planning/reach.hpp"

namespace freeplay::planning {
namespace {

TEST(Reach, DiscRadiusIsSqrtOfReachSquaredMinusHeightSquared) {
  EXPECT_DOUBLE_EQ(reach_disc_radius(0.5, 0.3), 0.4);
  EXPECT_DOUBLE_EQ(reach_disc_radius(0.5, 0.6), 0.0);
  EXPECT_TRUE(in_reach_disc({0.39, 0.0}, {0.0, 0.0}, 0.5, 0.3));
  EXPECT_FALSE(in_reach_disc({0.41, 0.0}, {0.0, 0.0}, 0.5, 0.3));
  EXPECT_FALSE(in_reach_disc({0.4, 0.0}, {0.0, 0.0}, 0.5, 0.3));  // strict, as the play policy
  EXPECT_TRUE(in_reach_disc({0.3, -0.35}, {0.3, -0.05}, 0.5, 0.2));
  EXPECT_FALSE(in_reach_disc({0.0, 0.0}, {0.0, 0.0}, 0.5, 0.5));
}

TEST(Layout, ItemsAreDistinctInsideThePlayAreaAndApart) {
  const auto shapes = approximate_item_shapes();
  ASSERT_EQ(shapes.size(), 10U);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Rng rng(seed);
    const Layout layout = random_layout(shapes, 10, rng);
    ASSERT_EQ(layout.items.size(), 10U);
    std::set<std::string> names;
    for (std::size_t i = 0; i < layout.items.size(); ++i) {
      names.insert(layout.items[i].name);
      for (const auto& v : layout.items[i].footprint) {
        EXPECT_GE(v.x(), 0.0);
        EXPECT_LT(v.x(), 0.528);
        EXPECT_LE(v.y(), 0.0);
        EXPECT_GE(v.y(), -0.335);
      }
      for (std::size_t j = 0; j < i; ++j) {
        EXPECT_GE(polygon_distance(layout.items[i].footprint, layout.items[j].footprint), 0.005);
      }
    }
    EXPECT_EQ(names.size(), 10U);
  }
}

TEST(Layout, SameSeedSameLayoutAndBadCountsAreInputErrors) {
  const auto shapes = approximate_item_shapes();
  Rng a(7);
  Rng b(7);
  const Layout first = random_layout(shapes, 5, a);
  const Layout second = random_layout(shapes, 5, b);
  ASSERT_EQ(first.items.size(), 5U);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(first.items[i].name, second.items[i].name);
    EXPECT_EQ(first.items[i].pose.x, second.items[i].pose.x);
    EXPECT_EQ(first.items[i].pose.theta, second.items[i].pose.theta);
  }
  EXPECT_EQ(first.obstacles().size(), 5U);
  Rng rng(1);
  EXPECT_THROW(random_layout(shapes, 11, rng), InputError);
  EXPECT_THROW(random_layout(shapes, -1, rng), InputError);
  EXPECT_TRUE(random_layout(shapes, 0, rng).items.empty());
}

TEST(PolygonDistance, TouchingOverlappingAndApart) {
  const Polygon2 a = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Polygon2 b = {{2, 0}, {3, 0}, {3, 1}, {2, 1}};
  const Polygon2 cross = {{0.5, -1}, {0.6, -1}, {0.6, 2}, {0.5, 2}};  // crosses a with no vertex inside it
  EXPECT_DOUBLE_EQ(polygon_distance(a, b), 1.0);
  EXPECT_TRUE(polygons_intersect(a, cross));
  EXPECT_DOUBLE_EQ(polygon_distance(a, cross), 0.0);
  EXPECT_FALSE(polygons_intersect(a, b));
}

}  // namespace
}  // namespace freeplay::planning
