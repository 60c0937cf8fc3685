#include <gtest/gtest.h>

#include "freeplay/core/frames.hpp"
#include "freeplay/core/geometry.hpp"

using namespace freeplay;

TEST(FrameTree, ComposesThroughCommonAncestor) {
  FrameTree tree;
  tree.set("zebra", "sandtray", Pose2{0.1, -0.1, 0.0}.isometry(), 0.0);
  tree.set("touch1", "sandtray", Pose2{0.3, -0.2, 0.0}.isometry(), 0.0);
  const auto t = tree.lookup("zebra", "touch1");
  ASSERT_TRUE(t.has_value());
  EXPECT_TRUE(t->translation().isApprox(Eigen::Vector3d(0.2, -0.1, 0.0)));
  EXPECT_FALSE(tree.lookup("zebra", "elsewhere").has_value());
  tree.remove("touch1");
  EXPECT_FALSE(tree.has("touch1"));
}
