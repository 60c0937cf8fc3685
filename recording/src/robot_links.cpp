#include "freeplay/recording/robot_links.hpp"

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/nao_description.hpp"
#include "freeplay/stage/stage_state.hpp"

namespace freeplay::recording {

namespace {

// The MuJoCo name of `body`, or "body<id>" when it has none.
std::string link_name(const stage::StageModel& model, int body) {
  std::string name = stage::body_name(model, body);
  return !name.empty() ? name : fmt::format("body{}", body);
}

}  // namespace

NaoLinkFrames::NaoLinkFrames(double arm_reach_m) {
  stage::StageConfig config;
  config.scene = stage::SceneKind::child_robot;
  config.arm_reach = arm_reach_m;
  stage_ = std::make_unique<stage::Stage>(stage::StageModel::create(config), stage::StageMode::kinematic);
  const stage::StageModel& model = stage_->model();
  const int torso = model.nao().torso_body;
  for (int b = 1; b < stage::body_count(model); ++b) {  // MuJoCo numbers bodies parents first
    for (int a = stage::body_parent(model, b); a > 0; a = stage::body_parent(model, a)) {
      if (a == torso) {
        link_bodies_.push_back(b);
        break;
      }
    }
  }
}

NaoLinkFrames::~NaoLinkFrames() = default;

const std::vector<LinkTransform>& NaoLinkFrames::compute(const std::vector<std::string>& names,
                                                        const std::vector<double>& positions) {
  const auto& nao = stage_->model().nao();
  std::vector<std::pair<int, double>> qpos;
  for (std::size_t i = 0; i < names.size() && i < positions.size(); ++i) {
    const int joint = stage::nao_joint_index(names[i]);
    if (joint < 0) {
      throw InputError(fmt::format("'{}' is not a Nao joint", names[i]), "joint_states.name",
                       "the 26 joints of NAOqi's Body chain (HeadYaw … RHand)");
    }
    qpos.emplace_back(nao.qpos[static_cast<std::size_t>(joint)], positions[i]);
  }
  for (const auto& [address, value] : qpos) stage::set_qpos(*stage_, address, value);
  stage_->update_kinematics();
  const stage::StageModel& model = stage_->model();
  out_.clear();
  out_.push_back({"sandtray", "base_link", stage::body_pose(*stage_, nao.torso_body)});
  out_.push_back({"base_link", link_name(model, nao.torso_body), Eigen::Isometry3d::Identity()});
  for (const int b : link_bodies_) {
    const int parent = stage::body_parent(model, b);
    out_.push_back({link_name(model, parent), link_name(model, b),
                    stage::body_pose(*stage_, parent).inverse() * stage::body_pose(*stage_, b)});
  }
  return out_;
}

}  // namespace freeplay::recording
