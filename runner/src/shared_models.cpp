// The default shared models and the robot body backed by the stage's MuJoCo Nao.

#include <spdlog/spdlog.h>

#include "freeplay/agents/params.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/stage/nao_controller.hpp"
#include "freeplay/stage/stage.hpp"
#include "freeplay/stage/stage_model.hpp"
#include "freeplay/stage/stage_state.hpp"

namespace freeplay::runner {

namespace {

/// The MuJoCo Nao of the stage as the episode's robot body: `nao_behaviours` pointing and gaze on each pose.
class StageRobotBody final : public RobotBody {
 public:
  StageRobotBody(std::shared_ptr<const stage::StageModel> model, stage::StageMode mode)
      : stage_(std::move(model), mode), nao_(stage_) {
    nao_.go_to_posture(stage::NaoPosture::StandInit);
    if (stage_.mode() == stage::StageMode::kinematic) stage_.update_kinematics();
    const auto disc = nao_.arm_reach();
    reach_ = {disc.centre, disc.radius};
  }

  ReachDisc reach() const override { return reach_; }

  Vec2 follow_finger(const Vec2& p) override {
    nao_.look_at(Eigen::Vector3d(p.x(), p.y(), 0.0));
    const auto result = nao_.point_at(p);
    if (stage_.mode() == stage::StageMode::dynamic) {
      nao_.apply();
      stage_.step(kDynamicStepsPerPose);
      const auto tip = stage_.site_position(stage_.model().nao().fingertip_site);
      return tip.head<2>();
    }
    return result.fingertip.head<2>();
  }

  void look_at(const Eigen::Vector3d& point) override { nao_.look_at(point); }

  void point_at(const Vec2& p) override { nao_.point_at(p); }

  void rest() override { nao_.go_to_posture(stage::NaoPosture::StandInit); }

  Eigen::Vector3d child_face(const std::string& seat) const override {
    const auto& avatar = stage_.model().avatar(seat == "yellow" ? stage::ChildRole::yellow : stage::ChildRole::purple);
    if (avatar.eyes_site >= 0) return stage_.site_position(avatar.eyes_site);
    // The purple child's face when the scene has no avatar there: across the table, at seated eye height.
    return {0.3, -0.6, 0.25};
  }

  void joint_state(RobotSnapshot& snapshot) const override {
    const auto& nao = stage_.model().nao();
    const bool dynamic = stage_.mode() == stage::StageMode::dynamic;
    for (int j = 0; j < stage::kNaoJointCount; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      snapshot.joint_names.emplace_back(stage::kNaoJointNames[ju]);
      snapshot.positions.push_back(stage::qpos(stage_, nao.qpos[ju]));
      snapshot.velocities.push_back(dynamic ? stage::qvel(stage_, nao.dof[ju]) : 0.0);
      snapshot.efforts.push_back(dynamic ? stage::actuator_joint_force(stage_, nao.dof[ju]) : 0.0);
    }
  }

 private:
  static constexpr int kDynamicStepsPerPose = 50;  // 0.1 s of 2 ms physics steps per 10 Hz pose
  stage::Stage stage_;
  stage::NaoController nao_;
  ReachDisc reach_;
};

}  // namespace

const SharedModels& SharedModels::shipped() {
  static const SharedModels models = load_default();
  return models;
}

SharedModels SharedModels::load_default() {
  SharedModels m;
  m.catalogue = std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default());
  m.child_params = std::make_shared<const agents::ChildModelParams>(agents::default_child_model_params());
  stage::StageConfig config;
  config.scene = stage::SceneKind::child_robot;
  auto kinematic_model = stage::StageModel::create(config);
  m.robot_body = [kinematic_model](stage::StageMode mode, double arm_reach) -> std::unique_ptr<RobotBody> {
    if (std::abs(arm_reach - kinematic_model->config().arm_reach) > 1e-12) {
      stage::StageConfig custom = kinematic_model->config();
      custom.arm_reach = arm_reach;
      return std::make_unique<StageRobotBody>(stage::StageModel::create(custom), mode);
    }
    return std::make_unique<StageRobotBody>(kinematic_model, mode);
  };
  return m;
}

}  // namespace freeplay::runner
