// NaoController: pointing IK accuracy and reachability, gaze limits, paths, dynamic tracking, joint limits.

#include <gtest/gtest.h>

#include <cmath>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/nao_controller.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

std::shared_ptr<const StageModel> robot_model() {
  static const auto model = [] {
    StageConfig config;
    config.scene = SceneKind::child_robot;
    return StageModel::create(config);
  }();
  return model;
}

void expect_within_joint_limits(const Stage& stage, double tolerance) {
  const mjModel* m = raw_model(stage.model());
  const NaoIndex& nao = stage.model().nao();
  for (int i = 0; i < kNaoJointCount; ++i) {
    const int joint = nao.joint[static_cast<size_t>(i)];
    const double q = raw_data(stage)->qpos[nao.qpos[static_cast<size_t>(i)]];
    EXPECT_GE(q, m->jnt_range[2 * joint] - tolerance) << kNaoJointNames[static_cast<size_t>(i)];
    EXPECT_LE(q, m->jnt_range[2 * joint + 1] + tolerance) << kNaoJointNames[static_cast<size_t>(i)];
  }
}

// Screen points near the robot (it stands at the yellow edge, y = 0, right shoulder over x ≈ 0.2).
const std::vector<Eigen::Vector2d> kReachable = {{0.20, -0.02}, {0.25, -0.04}, {0.15, -0.03}, {0.28, -0.02},
                                                 {0.22, -0.06}};

TEST(NaoController, PointsWithin5mmAtReachableTargets) {
  Stage stage(robot_model());
  NaoController nao(stage);
  for (const auto& target : kReachable) {
    const PointingResult result = nao.point_at(target);
    stage.update_kinematics();
    const Eigen::Vector3d tip = stage.site_position(stage.model().nao().fingertip_site);
    EXPECT_TRUE(result.reachable) << target.transpose() << " error " << result.error_m;
    EXPECT_LE((tip.head<2>() - target).norm(), 0.005) << target.transpose();
    EXPECT_GT(tip.z(), 0.0);  // never through the screen
    EXPECT_NEAR(tip.z(), NaoController::kHoverHeight, 0.03);
    expect_within_joint_limits(stage, 0.0);
  }
}

TEST(NaoController, ReportsUnreachableTargets) {
  Stage stage(robot_model());
  NaoController nao(stage);
  for (const Eigen::Vector2d& target : {Eigen::Vector2d(0.3, -0.30), Eigen::Vector2d(0.58, -0.2)}) {
    const PointingResult result = nao.point_at(target);
    EXPECT_FALSE(result.reachable) << target.transpose();
    EXPECT_GT(result.error_m, 0.005);
    expect_within_joint_limits(stage, 0.0);
  }
  EXPECT_THROW(nao.point_at(Eigen::Vector2d(std::nan(""), 0)), InputError);
}

// Beyond the whole arm's length the IK starts from the default pointing pose only, so the stretched arm does not
// depend on where the arm was before (the arm does not jump between solutions as an item is dragged out of reach).
TEST(NaoController, BeyondTheArmsLengthTheStretchDoesNotDependOnThePreviousPose) {
  const Eigen::Vector2d far_away(0.3, -0.30);
  std::vector<PointingResult> stretched;
  for (const auto& before : kReachable) {
    Stage stage(robot_model());
    NaoController nao(stage);
    nao.point_at(before);
    stretched.push_back(nao.point_at(far_away));
  }
  for (const auto& result : stretched) {
    EXPECT_FALSE(result.reachable);
    EXPECT_EQ(result.fingertip, stretched.front().fingertip);
  }
}

TEST(NaoController, ArmReachDiscUsesTheShoulderHeight) {
  Stage stage(robot_model());
  NaoController nao(stage);
  const ArmReachDisc disc = nao.arm_reach();
  const Eigen::Vector3d shoulder =
      Eigen::Map<const Eigen::Vector3d>(raw_data(stage)->xpos + 3 * stage.model().nao().rshoulder_body);
  EXPECT_FALSE(disc.too_high);
  EXPECT_NEAR(disc.radius, std::sqrt(0.25 - shoulder.z() * shoulder.z()), 1e-12);
  EXPECT_TRUE(disc.centre.isApprox(shoulder.head<2>()));
  EXPECT_GT(shoulder.z(), 0.1);  // the shoulder is above the table, not below it
}

TEST(NaoController, LooksAtThePurpleChildAcrossTheTable) {
  Stage stage(robot_model());
  NaoController nao(stage);
  const Eigen::Vector3d target = stage.site_position(stage.model().avatar(ChildRole::purple).eyes_site);
  const GazeResult gaze = nao.look_at(target);
  EXPECT_FALSE(gaze.clamped);
  stage.update_kinematics();
  // the head's forward ray from the gaze point (CameraTop's position; the camera itself tilts 1.2° lower)
  const int gaze_site = stage.model().nao().gaze_site;
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> head(raw_data(stage)->site_xmat + 9 * gaze_site);
  const Eigen::Vector3d to_target = (target - stage.site_position(gaze_site)).normalized();
  EXPECT_GT(head.col(0).dot(to_target), std::cos(0.5 * M_PI / 180.0));
}

TEST(NaoController, HeadPitchIsClampedByTheYawDependentLimits) {
  Stage stage(robot_model());
  NaoController nao(stage);
  // the screen centre is too far below CameraTop's line of sight for the head pitch limit (29.5° at yaw 0)
  const GazeResult centre = nao.look_at(Eigen::Vector3d(0.3, -0.1675, 0.0));
  EXPECT_TRUE(centre.clamped);
  EXPECT_NEAR(centre.pitch, head_pitch_range(centre.yaw).max, 1e-12);
  // far to the robot's left and far below: needs more pitch than allowed at that yaw
  const Eigen::Vector3d neck =
      Eigen::Map<const Eigen::Vector3d>(raw_data(stage)->xpos + 3 * stage.model().nao().neck_body);
  const GazeResult gaze = nao.look_at(neck + Eigen::Vector3d(0.3, -0.3, -0.6));
  EXPECT_TRUE(gaze.clamped);
  EXPECT_NEAR(gaze.pitch, head_pitch_range(gaze.yaw).max, 1e-12);
  EXPECT_GT(std::abs(gaze.yaw), 0.5);
  // straight behind: yaw saturates at the joint limit
  const GazeResult behind = nao.look_at(neck + Eigen::Vector3d(-0.01, 1.0, 0.0));
  EXPECT_LE(std::abs(behind.yaw), 2.0857);
  expect_within_joint_limits(stage, 0.0);
}

TEST(NaoController, PathsInterpolateAndRejectBadTimes) {
  Stage stage(robot_model());
  NaoController nao(stage);
  EXPECT_THROW(nao.follow_path({}), InputError);
  EXPECT_THROW(nao.follow_path({{0.0, {0.2, -0.02}}, {0.0, {0.25, -0.02}}}), InputError);
  EXPECT_THROW(nao.path_point(0.0), InputError);
  nao.follow_path({{1.0, {0.2, -0.02}}, {2.0, {0.3, -0.04}}});
  EXPECT_TRUE(nao.path_point(0.0).isApprox(Eigen::Vector2d(0.2, -0.02)));
  EXPECT_TRUE(nao.path_point(1.5).isApprox(Eigen::Vector2d(0.25, -0.03)));
  EXPECT_TRUE(nao.path_point(9.0).isApprox(Eigen::Vector2d(0.3, -0.04)));
  const PointingResult result = nao.update(1.5);
  EXPECT_TRUE(result.reachable);
}

TEST(NaoControllerDynamic, ArmTracksAPointingTrajectoryWithinBounds) {
  Stage stage(robot_model(), StageMode::dynamic);
  NaoController nao(stage);
  nao.follow_path({{0.0, {0.15, -0.03}}, {0.5, {0.15, -0.03}}, {2.0, {0.28, -0.05}}, {3.0, {0.28, -0.05}}});
  const int fingertip = stage.model().nao().fingertip_site;
  double worst_moving = 0.0;
  constexpr double kControlPeriod = 0.01;  // 100 Hz targets, physics at 2 ms
  const int steps_per_tick = static_cast<int>(std::lround(kControlPeriod / raw_model(stage.model())->opt.timestep));
  ASSERT_LE(raw_model(stage.model())->opt.timestep, 0.002);
  while (stage.time() < 3.0 - 1e-9) {
    nao.update(stage.time() + kControlPeriod);
    stage.step(steps_per_tick);
    expect_within_joint_limits(stage, 0.002);
    const double error = (stage.site_position(fingertip).head<2>() - nao.path_point(stage.time())).norm();
    if (stage.time() > 0.5) {  // StandInit's hands start just above the table top, slightly lower than the screen
      worst_moving = std::max(worst_moving, error);
      ASSERT_GT(stage.site_position(fingertip).z(), 0.0) << stage.time();
    }
  }
  const double final_error = (stage.site_position(fingertip).head<2>() - nao.path_point(3.0)).norm();
  EXPECT_LT(worst_moving, 0.01);  // 13 cm drag in 1.5 s (measured: 5 mm worst, 2.6 mm mean)
  EXPECT_LT(final_error, 0.005);
}

TEST(NaoControllerDynamic, GoToPostureHoldsStill) {
  Stage stage(robot_model(), StageMode::dynamic);
  NaoController nao(stage);
  nao.go_to_posture(NaoPosture::StandInit);
  for (int i = 0; i < 100; ++i) {
    nao.apply();
    stage.step(5);
  }
  const NaoJointVector q = nao.joint_positions();
  for (int i = 0; i < kNaoJointCount; ++i) {
    EXPECT_NEAR(q[static_cast<size_t>(i)], posture_angles(NaoPosture::StandInit)[static_cast<size_t>(i)], 0.01)
        << kNaoJointNames[static_cast<size_t>(i)];
  }
}

TEST(NaoController, HandsOpenAndCloseWithinZeroToOne) {
  Stage stage(robot_model());
  NaoController nao(stage);
  const int right_hand = nao_joint_index("RHand");
  const int tip = stage.model().nao().fingertip_site;
  stage.update_kinematics();
  const Eigen::Vector3d tip_before = stage.site_position(tip);
  nao.set_hands(2.0, -1.0);
  EXPECT_DOUBLE_EQ(nao.joint_positions()[static_cast<size_t>(nao_joint_index("LHand"))], 1.0);
  EXPECT_DOUBLE_EQ(nao.joint_positions()[static_cast<size_t>(right_hand)], 0.0);
  stage.update_kinematics();
  EXPECT_TRUE(stage.site_position(tip).isApprox(tip_before));  // the pointing fingertip does not depend on the hand
  // closing curls the finger geoms down towards the palm
  const mjModel* m = raw_model(stage.model());
  const int finger = mj_name2id(m, mjOBJ_GEOM, "r_finger1");
  const double closed_z = raw_data(stage)->geom_xpos[3 * finger + 2];
  nao.set_hands(1.0, 1.0);
  stage.update_kinematics();
  EXPECT_GT(raw_data(stage)->geom_xpos[3 * finger + 2], closed_z);
}

TEST(NaoController, NeedsARobotInTheScene) {
  Stage stage(StageModel::create({}));
  EXPECT_THROW(NaoController nao(stage), InputError);
}

}  // namespace
}  // namespace freeplay::stage
