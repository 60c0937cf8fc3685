// The typed reads of the stage's MuJoCo state (stage_state.hpp) and the NAO's self-collision checks.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <memory>
#include <set>
#include <string>

#include "freeplay/stage/nao_description.hpp"
#include "freeplay/stage/nao_self_collision.hpp"
#include "freeplay/stage/stage_state.hpp"

namespace freeplay::stage {
namespace {

std::shared_ptr<const StageModel> robot_model() {
  StageConfig config;
  config.scene = SceneKind::child_robot;
  return StageModel::create(config);
}

int address(const StageModel& model, std::string_view joint) {
  return model.nao().qpos[static_cast<std::size_t>(nao_joint_index(joint))];
}

TEST(StageState, JointCoordinatesReadBackMoveTheBodiesAndHashTheState) {
  const auto model = robot_model();
  Stage a(model);
  Stage b(model);
  EXPECT_EQ(state_hash(a), state_hash(b));
  const int yaw = address(*model, "HeadYaw");
  const Eigen::Matrix3d before = body_rotation(a, model->nao().head_body);
  set_qpos(a, yaw, 0.5);
  a.update_kinematics();
  EXPECT_EQ(qpos(a, yaw), 0.5);
  EXPECT_EQ(qpos_all(a)[static_cast<std::size_t>(yaw)], 0.5);
  EXPECT_EQ(qpos_all(a).size(), qpos_names(*model).size());
  EXPECT_EQ(qvel_all(a).size(), qvel_all(b).size());
  EXPECT_NE(state_hash(a), state_hash(b));
  const Eigen::Matrix3d after = body_rotation(a, model->nao().head_body);
  EXPECT_GT((after - before).norm(), 0.1);
  EXPECT_LT((body_pose(a, model->nao().head_body).linear() - after).norm(), 1e-9);
  set_qpos(b, yaw, 0.5);
  EXPECT_EQ(state_hash(a), state_hash(b));
}

TEST(StageState, NamesParentsAndLimitsOfTheNao) {
  const auto model = robot_model();
  const int gripper = body_id(*model, "r_gripper");
  ASSERT_GT(gripper, 0);
  EXPECT_LT(gripper, body_count(*model));
  EXPECT_EQ(body_name(*model, gripper), "r_gripper");
  EXPECT_EQ(body_name(*model, body_parent(*model, gripper)), "r_wrist");
  EXPECT_EQ(body_id(*model, "no such body"), -1);
  EXPECT_EQ(qpos_names(*model)[static_cast<std::size_t>(address(*model, "HeadYaw"))], "HeadYaw");
  const int yaw = model->nao().joint[static_cast<std::size_t>(nao_joint_index("HeadYaw"))];
  const auto [lower, upper] = joint_range(*model, yaw);
  EXPECT_NEAR(lower, -2.0857, 1e-3);
  EXPECT_NEAR(upper, 2.0857, 1e-3);
  EXPECT_GE(dof_damping(*model, model->nao().dof[0]), 0.0);
}

TEST(StageState, MujocoVersionTextMatchesItsNumber) {
  const int n = mujoco_version_number();
  EXPECT_EQ(mujoco_version(), fmt::format("{}.{}.{}", n / 100, n / 10 % 10, n % 10));
}

TEST(NaoSelfCollision, StandInitIsFreeAndAHeadPitchedIntoTheTorsoCollidesOnce) {
  const auto model = robot_model();
  Stage stage(model);
  NaoSelfCollision collisions(*model, 0.001);
  EXPECT_GT(collisions.pairs(), 0U);
  bool any = true;
  EXPECT_EQ(collisions.update(stage, any), 0);
  EXPECT_FALSE(any);
  EXPECT_TRUE(collisions.hit().empty());
  const int pitch = model->nao().joint[static_cast<std::size_t>(nao_joint_index("HeadPitch"))];
  // Beyond the joint limit, chin into the chest: a pose the controller must report.
  set_qpos(stage, address(*model, "HeadPitch"), joint_range(*model, pitch).second + 0.6);
  stage.update_kinematics();
  EXPECT_EQ(collisions.update(stage, any), 1);
  EXPECT_TRUE(any);
  EXPECT_EQ(collisions.update(stage, any), 0);  // still colliding: no new onset
  EXPECT_TRUE(any);
  EXPECT_EQ(collisions.hit(), (std::set<std::string>{"torso_shell/head"}));
}

}  // namespace
}  // namespace freeplay::stage
