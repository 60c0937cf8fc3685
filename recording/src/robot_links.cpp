#include "freeplay/recording/robot_links.hpp"

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/nao_description.hpp"

namespace freeplay::recording {

namespace {

Eigen::Isometry3d body_pose(const mjData* d, int body) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]);
  pose.linear() = Eigen::Quaterniond(d->xquat[4 * body], d->xquat[4 * body + 1], d->xquat[4 * body + 2],
                                     d->xquat[4 * body + 3])
                      .normalized()
                      .toRotationMatrix();
  return pose;
}

std::string body_name(const mjModel* m, int body) {
  const char* name = mj_id2name(m, mjOBJ_BODY, body);
  return name != nullptr ? name : fmt::format("body{}", body);
}

}  // namespace

NaoLinkFrames::NaoLinkFrames(double arm_reach_m) {
  stage::StageConfig config;
  config.scene = stage::SceneKind::child_robot;
  config.arm_reach = arm_reach_m;
  stage_ = std::make_unique<stage::Stage>(stage::StageModel::create(config), stage::StageMode::kinematic);
  const mjModel* m = stage_->model().mj();
  const int torso = stage_->model().nao().torso_body;
  for (int b = 1; b < m->nbody; ++b) {  // MuJoCo numbers bodies parents first
    for (int a = m->body_parentid[b]; a > 0; a = m->body_parentid[a]) {
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
  for (const auto& [address, value] : qpos) stage_->data()->qpos[address] = value;
  stage_->update_kinematics();
  const mjModel* m = stage_->model().mj();
  const mjData* d = stage_->data();
  out_.clear();
  out_.push_back({"sandtray", "base_link", body_pose(d, nao.torso_body)});
  out_.push_back({"base_link", body_name(m, nao.torso_body), Eigen::Isometry3d::Identity()});
  for (const int b : link_bodies_) {
    const int parent = m->body_parentid[b];
    out_.push_back({body_name(m, parent), body_name(m, b), body_pose(d, parent).inverse() * body_pose(d, b)});
  }
  return out_;
}

}  // namespace freeplay::recording
