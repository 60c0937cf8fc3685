// Ground-truth keypoints: projected avatar keypoints land on the avatar in a rendered frame (OSMesa depth), and the
// recorder writes freeplay.poses.json in extract_poses' format.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "freeplay/recording/poses.hpp"
#include "freeplay/stage/avatar_controller.hpp"
#include "freeplay/stage/avatar_keypoints.hpp"
#include "freeplay/stage/renderer.hpp"

// Mesa keeps a few small allocations of its GL contexts until exit (OSMesaMakeCurrent, EGL drivers): not ours.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\nleak:libEGL_mesa.so\nleak:libgallium\nleak:libGLdispatch.so\nleak:libubsan.so\n";
}

namespace freeplay::recording {
namespace {

using stage::CocoPoint;

TEST(Poses, ProjectedKeypointsLandOnTheAvatarInARenderedFrame) {
  auto model = stage::StageModel::create({});
  stage::Stage stage(model);
  stage::AvatarController purple(stage, stage::ChildRole::purple);
  purple.look_at(Eigen::Vector3d(0.3, -0.17, 0.0));
  const Eigen::Vector2d target(0.3, -0.25);
  ASSERT_TRUE(purple.touch(target, stage::Hand::right).reachable);
  stage.update_kinematics();
  const auto k = stage::avatar_keypoints(stage, stage::ChildRole::purple);

  stage::Renderer renderer(model, {stage::GlBackend::osmesa, stage::VisualPreset::fast, 1280, 960});
  const auto& K = model->camera("camera_purple").color;
  const auto frame = renderer.render(stage, "camera_purple", {false, true, 0, 0, K});
  ASSERT_EQ(frame.depth_m.cols, K.width);
  // The rendered surface at a keypoint's pixel: a face point lies on it (it is on the head sphere); a joint lies
  // inside the limb, at most a limb's radius behind it; and never does the ray pass the point by (background).
  auto surface_gap = [&](const Eigen::Vector3d& p) {
    const auto ip = project(p, K, frame.sandtray_T_camera_optical);
    EXPECT_GT(ip.c, 0.0);
    const double z = (frame.sandtray_T_camera_optical.inverse() * p).z();
    const float depth = frame.depth_m.at<float>(static_cast<int>(std::lround(ip.y)), static_cast<int>(std::lround(ip.x)));
    return z - static_cast<double>(depth);
  };
  int on_face = 0;
  int beside = 0;
  for (const auto& p : k.face) {
    const double gap = surface_gap(p);
    on_face += std::abs(gap) < 0.015 ? 1 : 0;  // else behind the mouth or eyes, or hidden by the shoulder
    beside += gap < -0.05 ? 1 : 0;             // the ray misses the head: the far cheek's silhouette at most
  }
  EXPECT_GE(on_face, 60) << "of 70 face points on the rendered head";
  EXPECT_LE(beside, 2);
  for (const auto point : {CocoPoint::nose, CocoPoint::r_eye, CocoPoint::l_eye}) {
    EXPECT_NEAR(surface_gap(k.body[static_cast<std::size_t>(point)]), 0.0, 0.01) << static_cast<int>(point);
  }
  // The neck, shoulders and elbows are in camera_purple's view (the reaching hand is beyond its image edge).
  for (const auto point : {CocoPoint::neck, CocoPoint::r_shoulder, CocoPoint::l_shoulder, CocoPoint::r_elbow,
                           CocoPoint::l_elbow}) {
    const double gap = surface_gap(k.body[static_cast<std::size_t>(point)]);
    EXPECT_GT(gap, -0.005) << static_cast<int>(point);
    EXPECT_LT(gap, 0.09) << static_cast<int>(point);
  }
  EXPECT_EQ(project(k.body[static_cast<std::size_t>(CocoPoint::r_wrist)], K, frame.sandtray_T_camera_optical).c, 0.0);
  // The right wrist is near the fingertip that touches the screen.
  EXPECT_LT((k.hands[0][0] - k.body[static_cast<std::size_t>(CocoPoint::r_wrist)]).norm(), 1e-12);
  EXPECT_LT((k.body[static_cast<std::size_t>(CocoPoint::r_wrist)] - Eigen::Vector3d(target.x(), target.y(), 0.0)).norm(),
            0.2);
}

TEST(Poses, ProjectionIsAPinholeAndRefusesPointsBehindOrOutside) {
  const stage::CameraIntrinsics K{640, 480, 500.0, 500.0, 320.0, 240.0};
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const auto p = project(Eigen::Vector3d(0.1, -0.05, 1.0), K, I);
  EXPECT_DOUBLE_EQ(p.x, 370.0);
  EXPECT_DOUBLE_EQ(p.y, 215.0);
  EXPECT_EQ(p.c, 1.0);
  EXPECT_EQ(project(Eigen::Vector3d(0.1, 0.0, -1.0), K, I).c, 0.0);
  EXPECT_EQ(project(Eigen::Vector3d(5.0, 0.0, 1.0), K, I).c, 0.0);
}

}  // namespace
}  // namespace freeplay::recording
