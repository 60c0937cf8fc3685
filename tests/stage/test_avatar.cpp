// AvatarController: hands reach touch points, heads look at targets.

#include <gtest/gtest.h>

#include <cmath>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/avatar_controller.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

std::shared_ptr<const StageModel> children_model() {
  static const auto model = StageModel::create({});
  return model;
}

TEST(Avatar, HandReachesANearTouchPoint) {
  Stage stage(children_model());
  AvatarController purple(stage, ChildRole::purple);
  const Eigen::Vector2d point(0.35, -0.27);  // near half of the screen, purple side
  const TouchResult touch = purple.touch(point);
  EXPECT_TRUE(touch.reachable);
  EXPECT_LT(touch.error_m, 0.005);
  const Eigen::Vector3d tip = stage.site_position(stage.model().avatar(ChildRole::purple).hand_tip_site[0]);
  EXPECT_LT((tip - Eigen::Vector3d(point.x(), point.y(), 0.0)).norm(), 0.005);
}

TEST(Avatar, LeansForwardForFartherPointsAndReportsUnreachableOnes) {
  Stage stage(children_model());
  AvatarController yellow(stage, ChildRole::yellow);
  const TouchResult near = yellow.touch({0.3, -0.05}, Hand::left);
  const TouchResult middle = yellow.touch({0.3, -0.30}, Hand::left);
  EXPECT_TRUE(near.reachable);
  EXPECT_TRUE(middle.reachable);
  EXPECT_GT(middle.lean, near.lean);
  const TouchResult far = yellow.touch({0.3, -0.70}, Hand::left);  // beyond the table
  EXPECT_FALSE(far.reachable);
  EXPECT_GT(far.error_m, 0.005);
  EXPECT_THROW(yellow.touch({std::nan(""), 0.0}), InputError);
}

TEST(Avatar, HeadTurnsToLookAtATarget) {
  Stage stage(children_model());
  AvatarController purple(stage, ChildRole::purple);
  const int eyes = stage.model().avatar(ChildRole::purple).eyes_site;
  for (const Eigen::Vector3d& target : {Eigen::Vector3d(0.1, -0.1, 0.0), Eigen::Vector3d(0.3, 0.4, 0.5),
                                       Eigen::Vector3d(0.6, -0.3, 0.0)}) {
    const GazeResult gaze = purple.look_at(target);
    EXPECT_FALSE(gaze.clamped);
    stage.update_kinematics();
    const Eigen::Vector3d eye = stage.site_position(eyes);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> frame(raw_data(stage)->site_xmat + 9 * eyes);
    EXPECT_GT(frame.col(0).dot((target - eye).normalized()), std::cos(2.0 * M_PI / 180.0)) << target.transpose();
  }
  const GazeResult behind = purple.look_at(Eigen::Vector3d(0.3, -2.0, 0.5));
  EXPECT_TRUE(behind.clamped);
}

TEST(Stage, StepNeedsDynamicMode) {
  Stage stage(children_model());
  EXPECT_THROW(stage.step(1), std::logic_error);
}

TEST(Avatar, TheYellowChildIsAbsentInChildRobotScenes) {
  StageConfig config;
  config.scene = SceneKind::child_robot;
  Stage stage(StageModel::create(config));
  EXPECT_THROW(AvatarController(stage, ChildRole::yellow), InputError);
  EXPECT_NO_THROW(AvatarController(stage, ChildRole::purple));
}

TEST(Avatar, DynamicsLeaveAvatarsWhereTheControllerPutThem) {
  StageConfig config;
  config.scene = SceneKind::child_robot;
  Stage stage(StageModel::create(config), StageMode::dynamic);
  AvatarController purple(stage, ChildRole::purple);
  purple.touch({0.3, -0.25});
  const std::vector<double> before(raw_data(stage)->qpos, raw_data(stage)->qpos + raw_model(stage.model())->nq);
  stage.step(50);
  for (int address : stage.avatar_qpos())
    EXPECT_EQ(raw_data(stage)->qpos[address], before[static_cast<size_t>(address)]);
}

}  // namespace
}  // namespace freeplay::stage
