#pragma once
// Typed reads (and the one write) of the stage's MuJoCo model and state, so code outside stage/ never touches
// MuJoCo's raw model or state: joint coordinates, body poses and names, joint limits, the engine's version.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "freeplay/stage/stage.hpp"
#include "freeplay/stage/stage_model.hpp"

namespace freeplay::stage {

/// The joint angle (or coordinate) at qpos address `address`.
double qpos(const Stage& stage, int address);
/// Sets the coordinate at qpos address `address` (poses follow at the next update_kinematics).
void set_qpos(Stage& stage, int address, double value);
/// The velocity of degree of freedom `dof`.
double qvel(const Stage& stage, int dof);
/// The actuators' generalised force on degree of freedom `dof` (dynamic mode).
double actuator_joint_force(const Stage& stage, int dof);
/// The force (torque) actuator `actuator` applied in the last step (dynamic mode).
double actuator_force(const Stage& stage, int actuator);
/// Every joint coordinate, in qpos address order.
std::vector<double> qpos_all(const Stage& stage);
/// Every joint velocity, in dof order.
std::vector<double> qvel_all(const Stage& stage);
/// FNV-1a of the joint velocities' bytes chained onto that of the joint coordinates': equal states hash equal.
std::uint64_t state_hash(const Stage& stage);

/// Sandtray pose of a body after the last update (rotation from its normalised quaternion).
Eigen::Isometry3d body_pose(const Stage& stage, int body);
/// Sandtray orientation of a body after the last update, as MuJoCo's rotation matrix.
Eigen::Matrix3d body_rotation(const Stage& stage, int body);

/// Number of bodies (body 0 is the world; MuJoCo numbers bodies parents first).
int body_count(const StageModel& model);
/// The parent of `body` (0 for the world's children).
int body_parent(const StageModel& model, int body);
/// The id of the body called `name`, or -1.
int body_id(const StageModel& model, std::string_view name);
/// The name of `body`; empty when it has none.
std::string body_name(const StageModel& model, int body);
/// The name of `geom`; empty when it has none.
std::string geom_name(const StageModel& model, int geom);
/// The name of the joint that owns each qpos address (empty for a joint's further addresses).
std::vector<std::string> qpos_names(const StageModel& model);
/// The lower and upper limit of `joint` (rad or m).
std::pair<double, double> joint_range(const StageModel& model, int joint);
/// The damping of degree of freedom `dof` (N·m·s/rad).
double dof_damping(const StageModel& model, int dof);

/// The linked MuJoCo's version, e.g. "2.2.2".
std::string mujoco_version();
/// The linked MuJoCo's version number, e.g. 222.
int mujoco_version_number();

}  // namespace freeplay::stage
