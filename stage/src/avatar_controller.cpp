#include "freeplay/stage/avatar_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/pan_tilt.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

using Eigen::Vector3d;

Eigen::Matrix3d rotation_y(double angle) { return Eigen::AngleAxisd(angle, Vector3d::UnitY()).toRotationMatrix(); }

Vector3d body_offset(const mjModel* m, int body) { return Eigen::Map<const Vector3d>(m->body_pos + 3 * body); }

constexpr double kRestLean = 0.1;

}  // namespace

AvatarController::AvatarController(Stage& stage, ChildRole role) : stage_(stage), avatar_(stage.model().avatar(role)) {
  if (!avatar_.present) {
    throw InputError(std::string("the ") + std::string(child_role_name(role)) + " child is not in this scene",
                     "child", "purple (always), yellow (child-child scenes)");
  }
}

double AvatarController::qpos(int address) const { return raw_data(stage_)->qpos[address]; }

void AvatarController::set(int address, double value) {
  const mjModel* m = raw_model(stage_.model());
  int joint = -1;
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_qposadr[j] == address) joint = j;
  }
  raw_data(stage_)->qpos[address] = std::clamp(value, m->jnt_range[2 * joint], m->jnt_range[2 * joint + 1]);
}

void AvatarController::rest() {
  set(avatar_.lean, kRestLean);
  lower_hand(Hand::right);
  lower_hand(Hand::left);
  look_at(Vector3d(0.5 * SandtrayGeometry::screen_width, -0.5 * SandtrayGeometry::screen_height, 0.0));
}

void AvatarController::lower_hand(Hand hand) {
  // Hands rest flat on the table edge in front of the child, 10 cm either side of its midline.
  const double side = hand == Hand::right ? -1.0 : 1.0;
  const double to_edge = stage_.model().config().child_table_gap;
  const Vector3d rest_in_base(to_edge + 0.04, side * 0.10,
                              SandtrayGeometry::bezel_top_z + 0.015 - SandtrayGeometry::floor_z);
  set(avatar_.lean, kRestLean);
  reach(avatar_.sandtray_T_base * rest_in_base, hand);
}

GazeResult AvatarController::look_at(const Eigen::Vector3d& point) {
  const mjModel* m = raw_model(stage_.model());
  const int head = m->site_bodyid[avatar_.eyes_site];
  const Vector3d pelvis = body_offset(m, avatar_.pelvis_body);
  const Vector3d neck = body_offset(m, head);
  const Vector3d in_base = avatar_.sandtray_T_base.inverse() * point;
  const Vector3d target = rotation_y(qpos(avatar_.lean)).transpose() * (in_base - pelvis) - neck;
  const Vector3d eyes = Eigen::Map<const Vector3d>(m->site_pos + 3 * avatar_.eyes_site);
  const PanTilt wanted = pan_tilt_towards(target, eyes);
  set(avatar_.head_yaw, wanted.yaw);
  set(avatar_.head_pitch, wanted.pitch);
  GazeResult result{qpos(avatar_.head_yaw), qpos(avatar_.head_pitch), false};
  result.clamped = result.yaw != wanted.yaw || result.pitch != wanted.pitch;
  return result;
}

TouchResult AvatarController::touch(const Eigen::Vector2d& screen_point, Hand hand) {
  if (!screen_point.allFinite()) throw InputError("touch point is not finite", "screen point");
  return reach(Vector3d(screen_point.x(), screen_point.y(), 0.0), hand);
}

TouchResult AvatarController::reach(const Eigen::Vector3d& target_world, Hand hand) {
  const mjModel* m = raw_model(stage_.model());
  const auto side = static_cast<size_t>(hand);
  const int tip_site = avatar_.hand_tip_site[side];
  const int forearm = m->site_bodyid[tip_site];
  const int upper_arm = m->body_parentid[forearm];
  const double l1 = body_offset(m, forearm).x();
  const double l2 = m->site_pos[3 * tip_site];
  const Vector3d pelvis = body_offset(m, avatar_.pelvis_body);
  const Vector3d shoulder = body_offset(m, upper_arm);
  const Vector3d in_base = avatar_.sandtray_T_base.inverse() * target_world;

  // Lean forward only as much as the arm needs (bisection on the lean angle).
  auto distance_at = [&](double lean) { return (in_base - pelvis - rotation_y(lean) * shoulder).norm(); };
  const double reach = 0.98 * (l1 + l2);
  double lean = kRestLean;
  if (distance_at(lean) > reach) {
    const double lean_max = m->jnt_range[2 * m->dof_jntid[avatar_.dofs[0]] + 1];
    double lo = lean, hi = lean_max;
    if (distance_at(hi) > reach) {
      lean = hi;
    } else {
      for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (distance_at(mid) > reach ? lo : hi) = mid;
      }
      lean = hi;
    }
  }
  set(avatar_.lean, lean);
  const Vector3d t = rotation_y(qpos(avatar_.lean)).transpose() * (in_base - pelvis) - shoulder;
  const double yaw = std::atan2(t.y(), t.x());
  const double forward = std::hypot(t.x(), t.y());
  const double d = std::clamp(std::hypot(forward, t.z()), std::abs(l1 - l2) + 1e-6, l1 + l2);
  const double below = std::atan2(-t.z(), forward);
  const double alpha = std::acos(std::clamp((l1 * l1 + d * d - l2 * l2) / (2 * l1 * d), -1.0, 1.0));
  const double inner = std::acos(std::clamp((l1 * l1 + l2 * l2 - d * d) / (2 * l1 * l2), -1.0, 1.0));
  set(avatar_.shoulder_yaw[side], yaw);
  // Elbow below the shoulder–target line, as a seated child's arm hangs: the upper arm drops by alpha below the
  // line and the elbow flexes the forearm back up (negative pitch).
  set(avatar_.shoulder_pitch[side], below + alpha);
  set(avatar_.elbow[side], inner - std::numbers::pi);

  stage_.update_kinematics();
  TouchResult result;
  result.lean = qpos(avatar_.lean);
  result.error_m = (stage_.site_position(tip_site) - target_world).norm();
  result.reachable = result.error_m <= 0.005;
  return result;
}

}  // namespace freeplay::stage
