#include "freeplay/stage/stage_state.hpp"

#include <mujoco/mujoco.h>

#include "freeplay/core/rng.hpp"

namespace freeplay::stage {

namespace {

// The name of object `id` of `type`; empty when it has none.
std::string object_name(const mjModel* m, mjtObj type, int id) {
  const char* name = mj_id2name(m, type, id);
  return name != nullptr ? name : "";
}

}  // namespace

double qpos(const Stage& stage, int address) { return stage.data()->qpos[address]; }

void set_qpos(Stage& stage, int address, double value) { stage.data()->qpos[address] = value; }

double qvel(const Stage& stage, int dof) { return stage.data()->qvel[dof]; }

double actuator_joint_force(const Stage& stage, int dof) { return stage.data()->qfrc_actuator[dof]; }

double actuator_force(const Stage& stage, int actuator) { return stage.data()->actuator_force[actuator]; }

std::vector<double> qpos_all(const Stage& stage) {
  const mjData* d = stage.data();
  return {d->qpos, d->qpos + stage.model().mj()->nq};
}

std::vector<double> qvel_all(const Stage& stage) {
  const mjData* d = stage.data();
  return {d->qvel, d->qvel + stage.model().mj()->nv};
}

std::uint64_t state_hash(const Stage& stage) {
  const mjModel* m = stage.model().mj();
  const mjData* d = stage.data();
  const auto bytes = [](const mjtNum* p, int n) {
    return std::string_view(reinterpret_cast<const char*>(p), static_cast<std::size_t>(n) * sizeof(mjtNum));
  };
  return fnv1a64(bytes(d->qvel, m->nv), fnv1a64(bytes(d->qpos, m->nq)));
}

Eigen::Isometry3d body_pose(const Stage& stage, int body) {
  const mjtNum* x = stage.data()->xpos + 3 * body;
  const mjtNum* q = stage.data()->xquat + 4 * body;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x[0], x[1], x[2]);
  pose.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  return pose;
}

Eigen::Matrix3d body_rotation(const Stage& stage, int body) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(stage.data()->xmat + 9 * body);
}

int body_count(const StageModel& model) { return model.mj()->nbody; }

int body_parent(const StageModel& model, int body) { return model.mj()->body_parentid[body]; }

int body_id(const StageModel& model, std::string_view name) {
  return mj_name2id(model.mj(), mjOBJ_BODY, std::string(name).c_str());
}

std::string body_name(const StageModel& model, int body) { return object_name(model.mj(), mjOBJ_BODY, body); }

std::string geom_name(const StageModel& model, int geom) { return object_name(model.mj(), mjOBJ_GEOM, geom); }

std::vector<std::string> qpos_names(const StageModel& model) {
  const mjModel* m = model.mj();
  std::vector<std::string> names(static_cast<std::size_t>(m->nq));
  for (int j = 0; j < m->njnt; ++j) names[static_cast<std::size_t>(m->jnt_qposadr[j])] = object_name(m, mjOBJ_JOINT, j);
  return names;
}

std::pair<double, double> joint_range(const StageModel& model, int joint) {
  return {model.mj()->jnt_range[2 * joint], model.mj()->jnt_range[2 * joint + 1]};
}

double dof_damping(const StageModel& model, int dof) { return model.mj()->dof_damping[dof]; }

std::string mujoco_version() { return mj_versionString(); }

int mujoco_version_number() { return mj_version(); }

}  // namespace freeplay::stage
