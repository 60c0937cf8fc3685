#include "freeplay/stage/stage_state.hpp"

#include "freeplay/core/rng.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {

namespace {

// The name of object `id` of `type`; empty when it has none.
std::string object_name(const mjModel* m, mjtObj type, int id) {
  const char* name = mj_id2name(m, type, id);
  return name != nullptr ? name : "";
}

}  // namespace

double qpos(const Stage& stage, int address) { return raw_data(stage)->qpos[address]; }

void set_qpos(Stage& stage, int address, double value) { raw_data(stage)->qpos[address] = value; }

double qvel(const Stage& stage, int dof) { return raw_data(stage)->qvel[dof]; }

double actuator_joint_force(const Stage& stage, int dof) { return raw_data(stage)->qfrc_actuator[dof]; }

double actuator_force(const Stage& stage, int actuator) { return raw_data(stage)->actuator_force[actuator]; }

std::vector<double> qpos_all(const Stage& stage) {
  const mjData* d = raw_data(stage);
  return {d->qpos, d->qpos + raw_model(stage.model())->nq};
}

std::vector<double> qvel_all(const Stage& stage) {
  const mjData* d = raw_data(stage);
  return {d->qvel, d->qvel + raw_model(stage.model())->nv};
}

std::uint64_t state_hash(const Stage& stage) {
  const mjModel* m = raw_model(stage.model());
  const mjData* d = raw_data(stage);
  const auto bytes = [](const mjtNum* p, int n) {
    return std::string_view(reinterpret_cast<const char*>(p), static_cast<std::size_t>(n) * sizeof(mjtNum));
  };
  return fnv1a64(bytes(d->qvel, m->nv), fnv1a64(bytes(d->qpos, m->nq)));
}

Eigen::Isometry3d body_pose(const Stage& stage, int body) {
  const mjtNum* x = raw_data(stage)->xpos + 3 * body;
  const mjtNum* q = raw_data(stage)->xquat + 4 * body;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x[0], x[1], x[2]);
  pose.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  return pose;
}

Eigen::Matrix3d body_rotation(const Stage& stage, int body) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(raw_data(stage)->xmat + 9 * body);
}

int body_count(const StageModel& model) { return raw_model(model)->nbody; }

int body_parent(const StageModel& model, int body) { return raw_model(model)->body_parentid[body]; }

int body_id(const StageModel& model, std::string_view name) {
  return mj_name2id(raw_model(model), mjOBJ_BODY, std::string(name).c_str());
}

std::string body_name(const StageModel& model, int body) { return object_name(raw_model(model), mjOBJ_BODY, body); }

std::string geom_name(const StageModel& model, int geom) { return object_name(raw_model(model), mjOBJ_GEOM, geom); }

std::vector<std::string> qpos_names(const StageModel& model) {
  const mjModel* m = raw_model(model);
  std::vector<std::string> names(static_cast<std::size_t>(m->nq));
  for (int j = 0; j < m->njnt; ++j) names[static_cast<std::size_t>(m->jnt_qposadr[j])] = object_name(m, mjOBJ_JOINT, j);
  return names;
}

std::pair<double, double> joint_range(const StageModel& model, int joint) {
  return {raw_model(model)->jnt_range[2 * joint], raw_model(model)->jnt_range[2 * joint + 1]};
}

double dof_damping(const StageModel& model, int dof) { return raw_model(model)->dof_damping[dof]; }

std::string mujoco_version() { return mj_versionString(); }

int mujoco_version_number() { return mj_version(); }

}  // namespace freeplay::stage
