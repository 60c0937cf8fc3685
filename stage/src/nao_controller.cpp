#include "freeplay/stage/nao_controller.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/pan_tilt.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

using Eigen::Vector3d;
using RowMatrix3d = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// Right-arm joints used for pointing, as indices into kNaoJointNames.
constexpr std::array<int, 5> kRightArm = {20, 21, 22, 23, 24};
// A comfortable pointing posture the IK starts from and is pulled towards in its null space.
constexpr std::array<double, 5> kPointingSeed = {0.5, -0.25, 1.2, 0.9, 0.0};
constexpr int kLHipYawPitch = 8;
constexpr int kRHipYawPitch = 14;

Eigen::Quaterniond quat_at(const mjtNum* q) { return {q[0], q[1], q[2], q[3]}; }

}  // namespace

// Forward kinematics of the bodies from the right shoulder down to the fingertip site only, with MuJoCo's body and
// hinge-joint conventions (mj_kinematics), and the fingertip Jacobian of the pointing joints: the IK's inner loop
// without recomputing the whole scene.
class ArmChain {
 public:
  static constexpr size_t kMaxBodies = 16;
  using Key = std::array<double, 7 + kMaxBodies>;  // base position, base quaternion (w, x, y, z), the chain's qpos

  ArmChain(const mjModel* m, const NaoIndex& nao) : m_(m), site_(nao.fingertip_site) {
    for (int body = m->site_bodyid[site_]; body > 0; body = m->body_parentid[body]) {
      bodies_.push_back(body);
      if (body == nao.rshoulder_body) break;
    }
    std::reverse(bodies_.begin(), bodies_.end());
    // The Jacobian column of each hinge along the chain (-1: not a pointing joint).
    columns_.fill(-1);
    size_t hinge = 0;
    for (const int body : bodies_) {
      for (int j = m->body_jntadr[body]; j < m->body_jntadr[body] + m->body_jntnum[body] && hinge < kMaxBodies; ++j) {
        for (size_t c = 0; c < kRightArm.size(); ++c) {
          if (nao.joint[static_cast<size_t>(kRightArm[c])] == j) columns_[hinge] = static_cast<int>(c);
        }
        ++hinge;
      }
    }
    // A hinge keeps the distance from its anchor to everything beyond it, so the chain's length is the sum of the
    // anchor-to-anchor distances and the last anchor to the fingertip (any pose; here the model's reference one).
    const Vector3d tip = fingertip(Vector3d::Zero(), Eigen::Quaterniond::Identity(), m->qpos0, nullptr);
    if (hinge > 0 && hinge <= kMaxBodies) {
      root_anchor_ = anchors_[0];
      for (size_t h = 1; h < hinge; ++h) length_ += (anchors_[h] - anchors_[h - 1]).norm();
      length_ += (tip - anchors_[hinge - 1]).norm();
    } else {
      length_ = std::numeric_limits<double>::infinity();
    }
  }

  // False when no joint angles bring the fingertip within `xy_tolerance` of `target` on the screen plane with its
  // height in [z_min, z_max]: that region is farther from the first hinge than the chain is long.
  bool may_reach(const Vector3d& base_pos, const Eigen::Quaterniond& base_quat, const Vector3d& target,
                 double xy_tolerance, double z_min, double z_max) const {
    const Vector3d root = base_pos + base_quat * root_anchor_;
    const double across = std::max(0.0, (target.head<2>() - root.head<2>()).norm() - xy_tolerance);
    const double up = std::max({0.0, z_min - root.z(), root.z() - z_max});
    return std::hypot(across, up) <= length_;
  }

  // The body the chain hangs from (the shoulder's parent).
  int base() const { return m_->body_parentid[bodies_.front()]; }

  // Fingertip position for `qpos` with the base at (`base_pos`, `base_quat`); fills `jacobian` (3 × 5, pointing
  // joints in kRightArm order) when given.
  Vector3d fingertip(const Vector3d& base_pos, const Eigen::Quaterniond& base_quat, const mjtNum* qpos,
                     Eigen::Matrix<double, 3, 5>* jacobian) {
    Vector3d pos = base_pos;
    Eigen::Quaterniond quat = base_quat;
    int hinges = 0;
    for (const int body : bodies_) {
      // A zero offset rotates to zero, so skipping it leaves every sum unchanged (the NAO's joints sit at their
      // bodies' origins).
      const Eigen::Map<const Vector3d> body_pos(m_->body_pos + 3 * body);
      if (!body_pos.isZero(0.0)) pos += quat * body_pos;
      quat = quat * quat_at(m_->body_quat + 4 * body);
      for (int j = m_->body_jntadr[body]; j < m_->body_jntadr[body] + m_->body_jntnum[body]; ++j) {
        const Vector3d local_anchor = Eigen::Map<const Vector3d>(m_->jnt_pos + 3 * j);
        const Vector3d local_axis = Eigen::Map<const Vector3d>(m_->jnt_axis + 3 * j);
        const bool at_origin = local_anchor.isZero(0.0);
        const Vector3d anchor = at_origin ? pos : Vector3d(pos + quat * local_anchor);
        const int adr = m_->jnt_qposadr[j];
        quat = quat * Eigen::Quaterniond(Eigen::AngleAxisd(qpos[adr] - m_->qpos0[adr], local_axis));
        pos = at_origin ? anchor : Vector3d(anchor - quat * local_anchor);
        anchors_[static_cast<size_t>(hinges)] = anchor;
        axes_[static_cast<size_t>(hinges)] = quat * local_axis;
        ++hinges;
      }
      quat.normalize();
    }
    const Vector3d tip = pos + quat * Eigen::Map<const Vector3d>(m_->site_pos + 3 * site_);
    if (jacobian != nullptr) {
      jacobian->setZero();
      for (int h = 0; h < hinges; ++h) {
        const int column = columns_[static_cast<size_t>(h)];
        if (column < 0) continue;
        jacobian->col(column) = axes_[static_cast<size_t>(h)].cross(tip - anchors_[static_cast<size_t>(h)]);
      }
    }
    return tip;
  }

  // Inputs of one `fingertip` call with its Jacobian, and what it gave; compared bit for bit.
  struct Evaluation {
    Key key{};
    Vector3d tip = Vector3d::Zero();
    Eigen::Matrix<double, 3, 5> jacobian = Eigen::Matrix<double, 3, 5>::Zero();
    bool valid = false;
  };
  // Remembered evaluations (see NaoController::solve_pointing): the last pose of the latest first solve and retry,
  // and the retry's seed pose.
  enum Slot : std::size_t { kLastOfFirst, kLastOfRetry, kRetrySeed, kSlots };

  // The key of a `fingertip` call.
  Key key(const Vector3d& base_pos, const Eigen::Quaterniond& base_quat, const mjtNum* qpos) const {
    Key k{};
    for (int i = 0; i < 3; ++i) k[static_cast<size_t>(i)] = base_pos[i];
    k[3] = base_quat.w();
    k[4] = base_quat.x();
    k[5] = base_quat.y();
    k[6] = base_quat.z();
    size_t n = 7;
    for (const int body : bodies_) {
      for (int j = m_->body_jntadr[body]; j < m_->body_jntadr[body] + m_->body_jntnum[body] && n < k.size(); ++j) {
        k[n++] = qpos[m_->jnt_qposadr[j]];
      }
    }
    return k;
  }

  // `fingertip` with its Jacobian, answered from a remembered evaluation with bit-identical inputs when there is one.
  Vector3d fingertip_recalled(const Vector3d& base_pos, const Eigen::Quaterniond& base_quat, const mjtNum* qpos,
                              Eigen::Matrix<double, 3, 5>* jacobian) {
    const auto k = key(base_pos, base_quat, qpos);
    for (const Evaluation& e : memo_) {
      if (e.valid && std::memcmp(e.key.data(), k.data(), sizeof(double) * k.size()) == 0) {
        *jacobian = e.jacobian;
        return e.tip;
      }
    }
    return fingertip(base_pos, base_quat, qpos, jacobian);
  }

  // Remembers the evaluation `fingertip(base_pos, base_quat, qpos, &jacobian) == tip` in `slot`.
  void remember(Slot slot, const Vector3d& base_pos, const Eigen::Quaterniond& base_quat, const mjtNum* qpos,
                const Vector3d& tip, const Eigen::Matrix<double, 3, 5>& jacobian) {
    Evaluation& e = memo_[slot];
    e.key = key(base_pos, base_quat, qpos);
    e.tip = tip;
    e.jacobian = jacobian;
    e.valid = true;
  }

  // True when every joint of the chain is a hinge (what `fingertip` models).
  bool only_hinges() const {
    for (const int body : bodies_) {
      for (int j = m_->body_jntadr[body]; j < m_->body_jntadr[body] + m_->body_jntnum[body]; ++j) {
        if (m_->jnt_type[j] != mjJNT_HINGE) return false;
      }
    }
    return bodies_.size() <= kMaxBodies;
  }

 private:
  const mjModel* m_;
  int site_;
  std::vector<int> bodies_;
  std::array<int, kMaxBodies> columns_{};
  std::array<Vector3d, kMaxBodies> anchors_{};
  std::array<Vector3d, kMaxBodies> axes_{};
  std::array<Evaluation, kSlots> memo_{};
  Vector3d root_anchor_ = Vector3d::Zero();  // the first hinge's anchor in the base frame (no hinge moves it)
  double length_ = 0;  // the first hinge's anchor to the fingertip along the chain: no pose reaches farther
};

// A MuJoCo state for trial poses (placing the base, the arm's base pose, gravity feed-forward) and the gravity
// torques; the state is made on first use.
struct NaoController::Scratch {
  mjData* data = nullptr;
  std::vector<mjtNum> gravity;
  Scratch() = default;
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() { if (data != nullptr) mj_deleteData(data); }
};

NaoController::NaoController(Stage& stage)
    : stage_(stage), nao_(stage.model().nao()), scratch_(std::make_unique<Scratch>()) {
  if (!nao_.present) throw InputError("this stage has no NAO (use the child-robot scene)", "scene", "child-robot");
  const mjData* d = raw_data(stage_);
  for (int i = 0; i < kNaoJointCount; ++i) targets_[static_cast<size_t>(i)] = d->qpos[nao_.qpos[static_cast<size_t>(i)]];
}

NaoController::~NaoController() = default;

NaoJointVector NaoController::joint_positions() const {
  NaoJointVector q{};
  for (int i = 0; i < kNaoJointCount; ++i)
    q[static_cast<size_t>(i)] = raw_data(stage_)->qpos[nao_.qpos[static_cast<size_t>(i)]];
  return q;
}

void NaoController::set_joint_targets(const NaoJointVector& targets) {
  const mjModel* m = raw_model(stage_.model());
  for (int i = 0; i < kNaoJointCount; ++i) {
    const int joint = nao_.joint[static_cast<size_t>(i)];
    targets_[static_cast<size_t>(i)] =
        std::clamp(targets[static_cast<size_t>(i)], m->jnt_range[2 * joint], m->jnt_range[2 * joint + 1]);
  }
  targets_[kRHipYawPitch] = targets_[kLHipYawPitch];
  write_targets();
}

void NaoController::write_targets() {
  mjData* d = raw_data(stage_);
  if (stage_.mode() == StageMode::kinematic) {
    for (int i = 0; i < kNaoJointCount; ++i) d->qpos[nao_.qpos[static_cast<size_t>(i)]] = targets_[static_cast<size_t>(i)];
  }
  apply();
}

void NaoController::apply() {
  if (stage_.mode() != StageMode::dynamic) return;
  // Position targets plus the gravity torque at the target pose divided by the servo gain (feed-forward), so
  // the arm settles on the target instead of sagging by τ_gravity / kp.
  const mjModel* m = raw_model(stage_.model());
  if (scratch_->data == nullptr) scratch_->data = mj_makeData(m);
  mju_copy(scratch_->data->qpos, raw_data(stage_)->qpos, m->nq);
  mju_copy(scratch_->data->mocap_pos, raw_data(stage_)->mocap_pos, 3 * m->nmocap);
  mju_copy(scratch_->data->mocap_quat, raw_data(stage_)->mocap_quat, 4 * m->nmocap);
  for (int i = 0; i < kNaoJointCount; ++i)
    scratch_->data->qpos[nao_.qpos[static_cast<size_t>(i)]] = targets_[static_cast<size_t>(i)];
  mju_zero(scratch_->data->qvel, m->nv);
  mj_kinematics(m, scratch_->data);
  mj_comPos(m, scratch_->data);
  mj_comVel(m, scratch_->data);
  scratch_->gravity.resize(static_cast<size_t>(m->nv));
  mj_rne(m, scratch_->data, 0, scratch_->gravity.data());
  mjData* d = raw_data(stage_);
  for (int i = 0; i < kNaoJointCount; ++i) {
    const int actuator = nao_.actuator[static_cast<size_t>(i)];
    if (actuator < 0) continue;
    const double kp = m->actuator_gainprm[actuator * mjNGAIN];
    const double feed_forward = scratch_->gravity[static_cast<size_t>(nao_.dof[static_cast<size_t>(i)])] / kp;
    d->ctrl[actuator] = std::clamp(targets_[static_cast<size_t>(i)] + feed_forward, m->actuator_ctrlrange[2 * actuator],
                                   m->actuator_ctrlrange[2 * actuator + 1]);
  }
}

void NaoController::place_base(const NaoJointVector& posture) {
  const mjModel* m = raw_model(stage_.model());
  if (scratch_->data == nullptr) scratch_->data = mj_makeData(m);
  for (int i = 0; i < kNaoJointCount; ++i)
    scratch_->data->qpos[nao_.qpos[static_cast<size_t>(i)]] = posture[static_cast<size_t>(i)];
  const int mocap = nao_.torso_mocap;
  mju_zero3(scratch_->data->mocap_pos + 3 * mocap);
  mju_unit4(scratch_->data->mocap_quat + 4 * mocap);
  mj_kinematics(m, scratch_->data);
  const Vector3d l_sole = Eigen::Map<const Vector3d>(scratch_->data->site_xpos + 3 * nao_.l_sole_site);
  const Vector3d r_sole = Eigen::Map<const Vector3d>(scratch_->data->site_xpos + 3 * nao_.r_sole_site);
  const RowMatrix3d sole_r = Eigen::Map<const RowMatrix3d>(scratch_->data->site_xmat + 9 * nao_.l_sole_site);
  const Eigen::Matrix3d torso_r =
      Eigen::AngleAxisd(nao_.facing_yaw, Vector3d::UnitZ()).toRotationMatrix() * sole_r.transpose();
  // Soles' midpoint over the anchor; the lower sole on the floor (both are flat and level in every posture).
  const Vector3d l_world = torso_r * l_sole;
  const Vector3d r_world = torso_r * r_sole;
  Vector3d torso_p = nao_.sole_anchor - 0.5 * (l_world + r_world);
  torso_p.z() = nao_.sole_anchor.z() - std::min(l_world.z(), r_world.z());
  const Eigen::Quaterniond q(torso_r);
  mjData* d = raw_data(stage_);
  for (int k = 0; k < 3; ++k) d->mocap_pos[3 * mocap + k] = torso_p[k];
  d->mocap_quat[4 * mocap] = q.w();
  d->mocap_quat[4 * mocap + 1] = q.x();
  d->mocap_quat[4 * mocap + 2] = q.y();
  d->mocap_quat[4 * mocap + 3] = q.z();
}

void NaoController::go_to_posture(NaoPosture posture) {
  set_joint_targets(posture_angles(posture));  // clamps the table's 4-decimal values into the joint ranges
  place_base(targets_);
  if (stage_.mode() == StageMode::dynamic) {
    // The posture change itself is not simulated: the robot starts there at rest.
    mjData* d = raw_data(stage_);
    for (int i = 0; i < kNaoJointCount; ++i) {
      d->qpos[nao_.qpos[static_cast<size_t>(i)]] = targets_[static_cast<size_t>(i)];
      d->qvel[nao_.dof[static_cast<size_t>(i)]] = 0.0;
    }
    apply();
  }
}

GazeResult NaoController::look_at(const Eigen::Vector3d& point) {
  const mjModel* m = raw_model(stage_.model());
  const mjData* d = raw_data(stage_);
  // Pan/tilt is solved in the torso-aligned frame at the neck; the gaze origin is CameraTop's position. The torso
  // is the mocap body and the neck hangs from it with its joints at its origin, so neither needs the kinematics.
  Eigen::Matrix3d torso_r;
  Vector3d neck;
  bool neck_at_origin = m->body_parentid[nao_.neck_body] == nao_.torso_body && m->body_parentid[nao_.torso_body] == 0;
  for (int j = m->body_jntadr[nao_.neck_body]; neck_at_origin && j < m->body_jntadr[nao_.neck_body] + m->body_jntnum[nao_.neck_body]; ++j) {
    neck_at_origin = Eigen::Map<const Vector3d>(m->jnt_pos + 3 * j).isZero();
  }
  if (neck_at_origin) {
    const Eigen::Quaterniond torso_q = quat_at(d->mocap_quat + 4 * nao_.torso_mocap).normalized();
    torso_r = torso_q.toRotationMatrix();
    neck = Eigen::Map<const Vector3d>(d->mocap_pos + 3 * nao_.torso_mocap) +
           torso_q * Eigen::Map<const Vector3d>(m->body_pos + 3 * nao_.neck_body);
  } else {
    stage_.update_kinematics();
    torso_r = Eigen::Map<const RowMatrix3d>(d->xmat + 9 * nao_.torso_body);
    neck = Eigen::Map<const Vector3d>(d->xpos + 3 * nao_.neck_body);
  }
  const Vector3d target = torso_r.transpose() * (point - neck);
  const Vector3d eye_offset = Eigen::Map<const Vector3d>(m->site_pos + 3 * nao_.gaze_site);
  const PanTilt wanted = pan_tilt_towards(target, eye_offset);
  GazeResult result;
  result.yaw = std::clamp(wanted.yaw, -2.0857, 2.0857);
  const HeadPitchRange range = head_pitch_range(result.yaw);
  result.pitch = std::clamp(wanted.pitch, range.min, range.max);
  result.clamped = result.yaw != wanted.yaw || result.pitch != wanted.pitch;
  NaoJointVector targets = targets_;
  targets[0] = result.yaw;
  targets[1] = result.pitch;
  set_joint_targets(targets);
  return result;
}

// Copies the stage's state into the IK's scratch data (the Nao at its current targets) and poses the arm's base.
NaoController::ArmBase NaoController::load_arm() {
  const mjModel* m = raw_model(stage_.model());
  if (scratch_->data == nullptr) scratch_->data = mj_makeData(m);
  mju_copy(scratch_->data->qpos, raw_data(stage_)->qpos, m->nq);
  mju_copy(scratch_->data->mocap_pos, raw_data(stage_)->mocap_pos, 3 * m->nmocap);
  mju_copy(scratch_->data->mocap_quat, raw_data(stage_)->mocap_quat, 4 * m->nmocap);
  for (int i = 0; i < kNaoJointCount; ++i) {
    scratch_->data->qpos[nao_.qpos[static_cast<size_t>(i)]] = targets_[static_cast<size_t>(i)];
  }
  if (arm_chain_ == nullptr) {
    arm_chain_ = std::make_shared<ArmChain>(m, nao_);
    if (!arm_chain_->only_hinges()) throw std::logic_error("the NAO's right arm must be a chain of hinge joints");
  }
  // The arm's base does not move with the pointing joints: the torso is the NAO's mocap body (its pose is the
  // mocap pose); any other base is posed once by the full kinematics.
  ArmBase base;
  if (arm_chain_->base() == nao_.torso_body && m->body_parentid[nao_.torso_body] == 0) {
    base.position = Eigen::Map<const Vector3d>(scratch_->data->mocap_pos + 3 * nao_.torso_mocap);
    base.orientation = quat_at(scratch_->data->mocap_quat + 4 * nao_.torso_mocap).normalized();
  } else {
    mj_kinematics(m, scratch_->data);
    base.position = Eigen::Map<const Vector3d>(scratch_->data->xpos + 3 * arm_chain_->base());
    base.orientation = quat_at(scratch_->data->xquat + 4 * arm_chain_->base());
  }
  return base;
}

PointingResult NaoController::solve_pointing(const ArmBase& base, const Vector3d& target, const NaoJointVector& seed,
                                             bool retry, NaoJointVector* out) {
  const mjModel* m = raw_model(stage_.model());
  // Only the arm moves during a solve, and the seed's other joints are the current targets: the scratch data
  // loaded by `load_arm` needs just the seed's joints.
  for (int i = 0; i < kNaoJointCount; ++i)
    scratch_->data->qpos[nao_.qpos[static_cast<size_t>(i)]] = seed[static_cast<size_t>(i)];
  const Vector3d& base_pos = base.position;
  const Eigen::Quaterniond& base_quat = base.orientation;
  Eigen::Matrix<double, 3, 5> j;
  const Eigen::Vector3d weights(1.0, 1.0, 0.3);  // the on-screen position matters more than the hover height
  constexpr double kDamping = 0.01;
  Vector3d fingertip = Vector3d::Zero();
  double previous_error = std::numeric_limits<double>::infinity();
  // The chain is evaluated where the loop stops, so that pose needs no second evaluation; it and the retry's seed
  // pose are remembered, since the next solve usually starts from one of them (bit-identical inputs, same result).
  bool stopped = false;
  for (int iteration = 0; iteration < 150; ++iteration) {
    fingertip = iteration == 0 ? arm_chain_->fingertip_recalled(base_pos, base_quat, scratch_->data->qpos, &j)
                               : arm_chain_->fingertip(base_pos, base_quat, scratch_->data->qpos, &j);
    if (iteration == 0 && retry) {
      arm_chain_->remember(ArmChain::kRetrySeed, base_pos, base_quat, scratch_->data->qpos, fingertip, j);
    }
    const Vector3d error = (target - fingertip).cwiseProduct(weights);
    // Out of reach, the arm stretches towards the target and the error stops shrinking: stop there.
    stopped = (error.head<2>().norm() < 1e-4 && std::abs(error.z()) < 1e-3) ||
              (iteration >= 8 && previous_error - error.norm() < 1e-5);
    if (stopped) {
      arm_chain_->remember(retry ? ArmChain::kLastOfRetry : ArmChain::kLastOfFirst, base_pos, base_quat,
                           scratch_->data->qpos, fingertip, j);
      break;
    }
    previous_error = error.norm();
    Eigen::Matrix<double, 5, 1> q, lo, hi, preferred;
    for (size_t c = 0; c < kRightArm.size(); ++c) {
      const int k = kRightArm[c];
      for (int r = 0; r < 3; ++r) j(r, static_cast<Eigen::Index>(c)) *= weights[r];
      const int joint = nao_.joint[static_cast<size_t>(k)];
      q[static_cast<Eigen::Index>(c)] = scratch_->data->qpos[nao_.qpos[static_cast<size_t>(k)]];
      lo[static_cast<Eigen::Index>(c)] = m->jnt_range[2 * joint];
      hi[static_cast<Eigen::Index>(c)] = m->jnt_range[2 * joint + 1];
      preferred[static_cast<Eigen::Index>(c)] = kPointingSeed[c];
    }
    const Eigen::Matrix3d jjt = j * j.transpose() + kDamping * kDamping * Eigen::Matrix3d::Identity();
    // (JJᵀ + λ²I)⁻¹ one column at a time: Eigen solves a matrix right-hand side through its blocked triangular
    // solver (packing, blocking) and a vector one inline, with the same operations in the same order.
    const Eigen::LDLT<Eigen::Matrix3d> factors(jjt);
    Eigen::Matrix3d inverse;
    for (int c = 0; c < 3; ++c) inverse.col(c) = factors.solve(Eigen::Vector3d::Unit(c));
    const Eigen::Matrix<double, 5, 3> pseudo_inverse = j.transpose() * inverse;
    Eigen::Matrix<double, 5, 1> step = pseudo_inverse * error;
    const Eigen::Matrix<double, 5, 5> null_space = Eigen::Matrix<double, 5, 5>::Identity() - pseudo_inverse * j;
    step += null_space * (0.05 * (preferred - q));
    const double largest = step.cwiseAbs().maxCoeff();
    if (largest > 0.2) step *= 0.2 / largest;
    q = (q + step).cwiseMax(lo).cwiseMin(hi);
    for (size_t c = 0; c < kRightArm.size(); ++c) {
      scratch_->data->qpos[nao_.qpos[static_cast<size_t>(kRightArm[c])]] = q[static_cast<Eigen::Index>(c)];
    }
  }
  if (!stopped) fingertip = arm_chain_->fingertip(base_pos, base_quat, scratch_->data->qpos, nullptr);
  *out = seed;
  for (int k : kRightArm) (*out)[static_cast<size_t>(k)] = scratch_->data->qpos[nao_.qpos[static_cast<size_t>(k)]];
  PointingResult result;
  result.fingertip = fingertip;
  result.error_m = (target - fingertip).head<2>().norm();
  result.height_m = fingertip.z();
  result.reachable = result.error_m <= kReachTolerance && fingertip.z() > 0.0 && fingertip.z() < kMaxReachHeight;
  return result;
}

PointingResult NaoController::point_at(const Eigen::Vector2d& screen_point) {
  if (!screen_point.allFinite()) throw InputError("pointing target is not finite", "screen point");
  const Vector3d target(screen_point.x(), screen_point.y(), kHoverHeight);
  NaoJointVector pointing_seed = targets_;
  for (size_t c = 0; c < kRightArm.size(); ++c) pointing_seed[static_cast<size_t>(kRightArm[c])] = kPointingSeed[c];
  NaoJointVector solution{};
  const ArmBase base = load_arm();
  if (!arm_chain_->may_reach(base.position, base.orientation, target, kReachTolerance, 0.0, kMaxReachHeight)) {
    // No start reaches a target beyond the whole arm, so only the stretch matters: solved once, from the default
    // pose (the start that stretched it best in most such poses when both ran), it does not depend on the last pose.
    const PointingResult stretched = solve_pointing(base, target, pointing_seed, true, &solution);
    set_joint_targets(solution);
    return stretched;
  }
  PointingResult best = solve_pointing(base, target, targets_, false, &solution);
  if (!best.reachable) {
    NaoJointVector second{};
    const PointingResult retry = solve_pointing(base, target, pointing_seed, true, &second);
    if (retry.error_m < best.error_m) {
      best = retry;
      solution = second;
    }
  }
  set_joint_targets(solution);
  return best;
}

void NaoController::follow_path(std::vector<TimedScreenPoint> path) {
  if (path.empty()) throw InputError("a pointing path needs at least one point", "path", "one or more timed points");
  for (size_t i = 0; i < path.size(); ++i) {
    if (!path[i].point.allFinite() || !std::isfinite(path[i].time)) {
      throw InputError(fmt::format("path point {} is not finite", i), fmt::format("path[{}]", i));
    }
    if (i > 0 && path[i].time <= path[i - 1].time) {
      throw InputError(fmt::format("path times must increase (point {} at {} s)", i, path[i].time),
                       fmt::format("path[{}].time", i), "strictly increasing times");
    }
  }
  path_ = std::move(path);
}

Eigen::Vector2d NaoController::path_point(double time) const {
  if (path_.empty()) throw InputError("no path set (call follow_path first)", "path");
  if (time <= path_.front().time) return path_.front().point;
  if (time >= path_.back().time) return path_.back().point;
  const auto next = std::upper_bound(path_.begin(), path_.end(), time,
                                     [](double t, const TimedScreenPoint& p) { return t < p.time; });
  const auto prev = next - 1;
  const double f = (time - prev->time) / (next->time - prev->time);
  return prev->point + f * (next->point - prev->point);
}

PointingResult NaoController::update(double time) { return point_at(path_point(time)); }

void NaoController::set_hands(double left_opening, double right_opening) {
  NaoJointVector targets = targets_;
  targets[static_cast<size_t>(nao_joint_index("LHand"))] = left_opening;
  targets[static_cast<size_t>(nao_joint_index("RHand"))] = right_opening;
  set_joint_targets(targets);
}

ArmReachDisc NaoController::arm_reach() const {
  const Vector3d shoulder = Eigen::Map<const Vector3d>(raw_data(stage_)->xpos + 3 * nao_.rshoulder_body);
  const double reach = stage_.model().config().arm_reach;
  ArmReachDisc disc;
  disc.centre = shoulder.head<2>();
  const double h = shoulder.z();  // the screen surface is the z = 0 plane
  disc.too_high = h > reach;
  disc.radius = disc.too_high ? 0.0 : std::sqrt(reach * reach - h * h);
  return disc;
}

}  // namespace freeplay::stage
