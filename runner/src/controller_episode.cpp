#include "freeplay/runner/controller_episode.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/core/statistics.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/planning/plan.hpp"
#include "freeplay/runner/controller_settings.hpp"
#include "freeplay/runner/move_driver.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/runner/versions.hpp"
#include "freeplay/results/run_folder.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/stage/nao_controller.hpp"
#include "freeplay/stage/nao_description.hpp"
#include "freeplay/stage/nao_self_collision.hpp"
#include "freeplay/stage/stage.hpp"
#include "freeplay/stage/stage_model.hpp"
#include "freeplay/stage/stage_state.hpp"

namespace freeplay::runner {

namespace {

using stage::kNaoJointCount;
using stage::NaoJointVector;
using Target = ControllerTarget;

constexpr double kPhysicsDtS = 0.002;      // the stage's MuJoCo timestep
constexpr int kControlSteps = 10;          // 20 ms control cycle (ALMotion's DCM/motion cycle)
constexpr int kControlTicksPerGameTick = 5;  // the game's and the /poses stream's 10 Hz
constexpr double kControlDtS = kPhysicsDtS * kControlSteps;
constexpr double kGameTickS = kControlDtS * kControlTicksPerGameTick;
constexpr double kPenetrationM = 0.001;    // geoms closer than −1 mm count as a self-collision
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kLHand = 7;
constexpr int kRHipYawPitch = 14;
constexpr int kRHand = 25;

// URDF velocity limits (rad/s) and efforts (N·m) of the V5, in kNaoJointNames order (nao-and-setup.md §1.4).
constexpr std::array<double, kNaoJointCount> kVelocityLimit = {
    8.268, 7.194, 8.268, 7.194, 8.268, 7.194, 24.62, 8.33,  4.162, 4.162, 6.402, 6.402, 6.402,
    4.162, 4.162, 4.162, 6.402, 6.402, 6.402, 4.162, 8.268, 7.194, 8.268, 7.194, 24.62, 8.33};
constexpr std::array<double, kNaoJointCount> kEffortLimit = {
    1.547, 1.532, 1.329, 1.7835, 1.547, 1.532, 0.4075, 0.292, 3.348, 3.348, 3.023, 3.023, 3.023,
    3.348, 3.348, 3.348, 3.023,  3.023, 3.023, 3.348,  1.329, 1.7835, 1.547, 1.532, 0.4075, 0.292};

// Joints in rad-valued metrics (margin, tracking, settling): every joint but the hands (0–1, unitless).
bool rad_joint(int j) { return j != kLHand && j != kRHand; }

std::string_view kind_name(Target::Kind kind) {
  switch (kind) {
    case Target::Kind::Point: return "point";
    case Target::Kind::Look: return "look";
    case Target::Kind::Move: return "move";
    case Target::Kind::Posture: return "posture";
    case Target::Kind::Wait: return "wait";
    case Target::Kind::RandomPoints: return "random_points";
  }
  return "?";
}

double max_of(const std::vector<double>& v) {
  if (v.empty()) return kNaN;
  return *std::max_element(v.begin(), v.end());
}

/// One controller episode: owns the stage, the Nao controller, a sandtray for item moves and the metrics.
class ControllerEpisode {
 public:
  ControllerEpisode(const scenario::Scenario& scenario, std::uint64_t seed, const SharedModels& models)
      : scenario_(scenario), spec_(scenario.controller), seeds_(seed),
        stage_model_(make_stage_model(scenario)),
        stage_(stage_model_, spec_.mode),
        nao_(stage_), tray_(models.catalogue, sim::SandtrayConfig{}, seeds_.stream("sandtray")),
        collisions_(*stage_model_, kPenetrationM) {
    dynamic_ = stage_.mode() == stage::StageMode::dynamic;
    nao_.go_to_posture(stage::NaoPosture::StandInit);
    stage_.update_kinematics();
    goal_ = nao_.joint_targets();
    reference_ = goal_;
    previous_q_ = nao_.joint_positions();
    tray_.signal(sim::Signal::StartFreeplay);
    tray_.drain_events();
    const auto disc = nao_.arm_reach();
    mover_.emplace(make_move_executor(scenario, disc.centre, disc.radius), seeds_.stream("planner"));
    trace_.interval_steps = spec_.trace_interval_steps;
    trace_.machine = trace_machine_kind();
    trace_.qpos_names = stage::qpos_names(*stage_model_);
    set_profile_speeds();
    expand_targets();
  }

  ControllerEpisodeResult run(const std::atomic<bool>& stop) {
    ControllerEpisodeResult result;
    const auto wall_start = std::chrono::steady_clock::now();
    checkpoint();
    for (std::size_t i = 0; i < targets_.size(); ++i) {
      if (stop.load(std::memory_order_relaxed)) {
        result.aborted = true;
        return result;
      }
      run_target(i, targets_[i]);
    }
    result.simulated_s = time();
    result.record = record();
    result.record["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    result.events = std::move(log_);
    result.trace = std::move(trace_);
    return result;
  }

 private:
  static std::shared_ptr<const stage::StageModel> make_stage_model(const scenario::Scenario& scenario) {
    stage::StageConfig config;
    config.scene = stage::SceneKind::child_robot;
    config.arm_reach = scenario.robot.arm_reach_m;
    return stage::StageModel::create(config);
  }

  double time() const { return static_cast<double>(steps_) * kPhysicsDtS; }

  void expand_targets() {
    Rng rng = seeds_.stream("controller.targets");
    for (const auto& t : spec_.targets) {
      if (t.kind != Target::Kind::RandomPoints) {
        targets_.push_back(t);
        continue;
      }
      const bool reach = t.region == "reach";
      for (int i = 0; i < t.count; ++i) {
        Target p;
        p.kind = Target::Kind::Point;
        const double x = reach ? rng.uniform(0.08, 0.32) : rng.uniform(0.0, sim::kScreenWidthM);
        const double y = reach ? rng.uniform(-0.10, -0.01) : rng.uniform(-sim::kScreenHeightM, 0.0);
        p.point = {x, y};
        targets_.push_back(std::move(p));
      }
    }
  }

  // ---- commanding ----------------------------------------------------------------------------------------------

  // Runs a NaoController command against the goal (not the interpolated reference) and keeps its joint targets
  // as the new goal; the actuators keep following the reference.
  template <typename Command>
  auto command(Command&& f) {
    nao_.set_joint_targets(goal_);
    auto out = f();
    goal_ = nao_.joint_targets();
    nao_.set_joint_targets(reference_);
    if (!dynamic_) stage_.update_kinematics();
    return out;
  }

  // The profile speed of each joint: speed_fraction × its velocity limit, and no faster than torque_fraction × its
  // effort limit can drive against the joint's damping.
  void set_profile_speeds() {
    const auto& nao = stage_model_->nao();
    for (int j = 0; j < kNaoJointCount; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      const double damping = stage::dof_damping(*stage_model_, nao.dof[ju]);
      double speed = spec_.speed_fraction * kVelocityLimit[ju];
      if (damping > 0.0) speed = std::min(speed, spec_.torque_fraction * kEffortLimit[ju] / damping);
      profile_speed_[ju] = speed;
    }
  }

  void advance_reference(double dt) {
    for (std::size_t j = 0; j < reference_.size(); ++j) {
      const double step = profile_speed_[j] * dt;
      reference_[j] += std::clamp(goal_[j] - reference_[j], -step, step);
    }
  }

  Eigen::Vector3d fingertip() const { return stage_.site_position(stage_model_->nao().fingertip_site); }

  // One 20 ms control cycle: moves the reference towards the goal at the profile speed in 2 ms increments (the
  // DCM's interpolation between motion cycles), commands it with gravity feed-forward, steps physics.
  void control_tick() {
    if (dynamic_) {
      for (int s = 0; s < kControlSteps; ++s) {
        advance_reference(kPhysicsDtS);
        nao_.set_joint_targets(reference_);
        stage_.step(1);
        ++steps_;
        sample(nullptr);
        if (steps_ % spec_.trace_interval_steps == 0) checkpoint();
      }
    } else {
      advance_reference(kControlDtS);
      nao_.set_joint_targets(reference_);
      stage_.update_kinematics();
      const auto q = nao_.joint_positions();
      NaoJointVector velocity{};
      for (std::size_t j = 0; j < velocity.size(); ++j) velocity[j] = (q[j] - previous_q_[j]) / kControlDtS;
      previous_q_ = q;
      const long before = steps_;
      steps_ += kControlSteps;
      sample(&velocity);
      if (steps_ / spec_.trace_interval_steps != before / spec_.trace_interval_steps) checkpoint();
    }
    bool any = false;
    collision_onsets_ += collisions_.update(stage_, any);
    if (any) collision_time_s_ += kControlDtS;
    ++control_ticks_;
  }

  // Records velocity, torque, joint-limit and tracking samples of the current state.
  void sample(const NaoJointVector* kinematic_velocity) {
    const auto& nao = stage_model_->nao();
    for (int j = 0; j < kNaoJointCount; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      const double q = stage::qpos(stage_, nao.qpos[ju]);
      const double v = kinematic_velocity != nullptr ? (*kinematic_velocity)[ju] : stage::qvel(stage_, nao.dof[ju]);
      if (std::fabs(v) / kVelocityLimit[ju] > peak_velocity_fraction_) {
        peak_velocity_fraction_ = std::fabs(v) / kVelocityLimit[ju];
        peak_velocity_at_ = fmt::format("{} at {:.3f} s", stage::kNaoJointNames[ju], time());
      }
      const int actuator = nao.actuator[ju];
      if (dynamic_ && actuator >= 0 && j != kRHipYawPitch &&
          std::fabs(stage::actuator_force(stage_, actuator)) / kEffortLimit[ju] > peak_torque_fraction_) {
        peak_torque_fraction_ = std::fabs(stage::actuator_force(stage_, actuator)) / kEffortLimit[ju];
        peak_torque_at_ = fmt::format("{} at {:.3f} s", stage::kNaoJointNames[ju], time());
      }
      if (!rad_joint(j)) continue;
      const int joint = nao.joint[ju];
      const auto [lower, upper] = stage::joint_range(*stage_model_, joint);
      const double margin = std::min(q - lower, upper - q);
      if (margin < limit_margin_) {
        limit_margin_ = margin;
        limit_margin_joint_ = std::string(stage::kNaoJointNames[ju]);
      }
      const double e = std::fabs(reference_[ju] - q);
      tracking_sq_ += e * e;
      ++tracking_n_;
      tracking_max_ = std::max(tracking_max_, e);
    }
  }

  void checkpoint() {
    TraceCheckpoint c;
    c.step = steps_;
    c.time = time();
    c.hash = stage::state_hash(stage_);
    c.qpos = stage::qpos_all(stage_);
    c.qvel = stage::qvel_all(stage_);
    trace_.checkpoints.push_back(std::move(c));
  }

  // Max |joint speed| over the rad-valued joints (finite difference in kinematic mode).
  double joint_speed() const {
    const auto& nao = stage_model_->nao();
    double fastest = 0.0;
    for (int j = 0; j < kNaoJointCount; ++j) {
      if (!rad_joint(j)) continue;
      fastest = std::max(fastest, std::fabs(stage::qvel(stage_, nao.dof[static_cast<std::size_t>(j)])));
    }
    return dynamic_ ? fastest : (reference_ == goal_ ? 0.0 : 1e9);
  }

  double joint_error_to_goal() const {
    const auto q = nao_.joint_positions();
    double worst = 0.0;
    for (int j = 0; j < kNaoJointCount; ++j) {
      if (rad_joint(j)) worst = std::max(worst, std::fabs(q[static_cast<std::size_t>(j)] - goal_[static_cast<std::size_t>(j)]));
    }
    return worst;
  }

  // Game tick (10 Hz): the move stream and the sandtray.
  void game_tick() {
    mover_->step(time(), tray_sink_);
    tray_.step(kGameTickS);
    for (auto& e : tray_.drain_events()) {
      const auto* message = e.get<events::InteractionEvent>();
      if (message && message->message.rfind("releasing_", 0) == 0) released_ = true;
    }
  }

  // Control ticks until `done` holds (checked after each tick) or `limit_s` passes; true when `done` held.
  template <typename Done>
  bool run_until(double limit_s, Done&& done) {
    const double end = time() + limit_s;
    while (time() < end - 1e-9) {
      if (control_ticks_ % kControlTicksPerGameTick == 0) game_tick();
      control_tick();
      if (done()) return true;
    }
    return false;
  }

  // Runs until settled (or timeout), then holds; returns the settle time since `since` (NaN when not settled).
  template <typename Settled>
  double settle(double since, Settled&& settled) {
    const bool ok = run_until(std::max(0.0, since + spec_.timeout_s - time()), [&] {
      return reference_ == goal_ && joint_speed() < spec_.settle_speed_rad_s && settled();
    });
    const double settle_s = ok ? time() - since : kNaN;
    if (ok && spec_.hold_s > 0) run_until(spec_.hold_s, [] { return false; });
    return settle_s;
  }

  /// The Nao following the move's finger stream: points at and looks at each pose (nao_behaviours).
  class Follower final : public planning::ArmFollower {
   public:
    explicit Follower(ControllerEpisode& episode) : episode_(episode) {}
    planning::FollowReport follow(const Vec2& finger, double /*t*/) override { return episode_.follow(finger); }

   private:
    ControllerEpisode& episode_;
  };

  /// Where a target's move acts: the sandtray's `/poses` (fake touches) and the Nao following them.
  class TraySink final : public MoveSink {
   public:
    explicit TraySink(ControllerEpisode& episode) : episode_(episode) {}
    planning::MoveWorld move_world() override { return sandtray_move_world(episode_.tray_); }
    planning::ArmFollower* arm() override { return &episode_.follower_; }
    void move_started(const policies::MoveItem& /*move*/, bool /*running*/, double /*t*/) override {}
    void finger(const planning::TimedPose& pose, double /*t*/) override {
      episode_.tray_.robot_pose(pose.position);
      episode_.last_finger_ = pose.position;
    }
    void move_ended(const policies::MoveItem& /*move*/, planning::MoveStatus /*status*/, events::MoveResult /*result*/,
                    double /*t*/) override {}

   private:
    ControllerEpisode& episode_;
  };

  planning::FollowReport follow(const Vec2& finger) {
    const auto result = command([&] {
      nao_.look_at(Eigen::Vector3d(finger.x(), finger.y(), 0.0));
      return nao_.point_at(finger);
    });
    commanded_tip_ = result.fingertip;
    return {fingertip().head<2>(), result.reachable};
  }

  // ---- targets ----------------------------------------------------------------------------------------------

  void run_target(std::size_t index, const Target& t) {
    const double start = time();
    events::TargetEnd out;
    out.index = index;
    out.kind = std::string(kind_name(t.kind));
    out.t_start = start;
    log_.emit({start, "controller", events::TargetStart{index, out.kind}});
    switch (t.kind) {
      case Target::Kind::Point: {
        const Eigen::Vector2d p(t.point[0], t.point[1]);
        const auto ik = command([&] { return nao_.point_at(p); });
        commanded_tip_ = ik.fingertip;
        const double settle_s = settle(start, [&] { return tip_settled(); });
        const double error_mm = (fingertip().head<2>() - p).norm() * 1000.0;
        out.point = t.point;
        out.reachable = ik.reachable;
        out.ik_error_mm = ik.error_m * 1000.0;
        out.error_mm = error_mm;
        fingertip_errors_mm_.push_back(error_mm);
        if (ik.reachable) reachable_errors_mm_.push_back(error_mm);
        finish_settle(out, settle_s);
        break;
      }
      case Target::Kind::Look: {
        const Eigen::Vector3d p(t.point[0], t.point[1], t.point[2]);
        const auto gaze = command([&] { return nao_.look_at(p); });
        const double settle_s = settle(start, [&] { return joint_error_to_goal() <= spec_.settle_tolerance_rad; });
        const double error_deg = gaze_error_deg(p);
        gaze_errors_deg_.push_back(error_deg);
        if (!gaze.clamped) unclamped_gaze_errors_deg_.push_back(error_deg);
        out.look = t.point;
        out.clamped = gaze.clamped;
        out.gaze_error_deg = error_deg;
        finish_settle(out, settle_s);
        break;
      }
      case Target::Kind::Posture: {
        const auto posture = stage::posture_from_name(t.posture);
        command([&] {
          nao_.set_joint_targets(stage::posture_angles(posture));
          return 0;
        });
        const double settle_s = settle(start, [&] { return joint_error_to_goal() <= spec_.settle_tolerance_rad; });
        out.posture = t.posture;
        out.joint_error_rad = joint_error_to_goal();
        finish_settle(out, settle_s);
        break;
      }
      case Target::Kind::Wait:
        run_until(t.seconds, [] { return false; });
        out.wait_s = t.seconds;
        break;
      case Target::Kind::Move: run_move(t, out); break;
      case Target::Kind::RandomPoints: break;  // expanded before the run
    }
    out.t_end = time();
    per_target_.push_back(events::data_of(out));
    log_.emit({time(), "controller", std::move(out)});
  }

  void run_move(const Target& t, events::TargetEnd& out) {
    if (t.from) tray_.place_item(t.item, Pose2{(*t.from)[0], (*t.from)[1], 0.0});
    const Vec2 to(t.point[0], t.point[1]);
    released_ = false;
    mover_->start({t.item, to}, time(), tray_sink_);
    out.item = t.item;
    out.to = t.point;
    // Stream the poses (the executor ends by itself; a generous cap guards against a stuck stream).
    run_until(600.0, [&] { return !mover_->moving(); });
    const auto& outcome = mover_->outcome();
    const double stream_end = time();
    out.status = std::string(planning::move_status_name(outcome.status));
    out.reason = outcome.reason();
    out.poses = outcome.poses_sent;
    if (outcome.status != planning::MoveStatus::Succeeded) {
      ++moves_failed_;
      return;
    }
    ++moves_succeeded_;
    const double settle_s = settle(stream_end, [&] { return tip_settled(); });
    const double error_mm = (fingertip().head<2>() - last_finger_).norm() * 1000.0;
    fingertip_errors_mm_.push_back(error_mm);
    if (outcome.sync.unreachable == 0) reachable_errors_mm_.push_back(error_mm);
    // The game releases the item 1 s after the last pose.
    run_until(std::max(0.0, stream_end + 1.5 - time()), [&] { return released_; });
    if (released_) mover_->observe_release(tray_.item(t.item).pose.position());
    const auto& final_outcome = mover_->outcome();
    if (final_outcome.placement_error_m) placement_errors_mm_.push_back(*final_outcome.placement_error_m * 1000.0);
    const auto& sync = final_outcome.sync;
    sync_mean_mm_.push_back(sync.mean_error_m * 1000.0);
    sync_max_mm_.push_back(sync.max_error_m * 1000.0);
    sync_lag_ms_.push_back(sync.best_lag_s * 1000.0);
    out.error_mm = error_mm;
    out.sync_error_mm_mean = sync.mean_error_m * 1000.0;
    out.sync_error_mm_max = sync.max_error_m * 1000.0;
    out.sync_lag_ms = sync.best_lag_s * 1000.0;
    out.unreachable_poses = sync.unreachable;
    out.placement_error_mm = final_outcome.placement_error_m ? *final_outcome.placement_error_m * 1000.0 : kNaN;
    finish_settle(out, settle_s);
  }

  bool tip_settled() const { return (fingertip() - commanded_tip_).head<2>().norm() <= spec_.settle_tolerance_m; }

  void finish_settle(events::TargetEnd& out, double settle_s) {
    out.settled = !std::isnan(settle_s);
    out.settle_s = settle_s;
    if (std::isnan(settle_s)) {
      ++unsettled_;
    } else {
      settle_times_s_.push_back(settle_s);
    }
  }

  double gaze_error_deg(const Eigen::Vector3d& target) const {
    const auto& nao = stage_model_->nao();
    const Eigen::Vector3d axis = stage::body_rotation(stage_, nao.head_body).col(0);
    const Eigen::Vector3d to = target - stage_.site_position(nao.gaze_site);
    const double c = std::clamp(axis.normalized().dot(to.normalized()), -1.0, 1.0);
    return std::acos(c) * 180.0 / 3.141592653589793;
  }

  nlohmann::json record() {
    nlohmann::json metrics;
    metrics["targets"] = targets_.size();
    metrics["fingertip_error_mm"]["mean"] = freeplay::mean(fingertip_errors_mm_);
    metrics["fingertip_error_mm"]["max"] = max_of(fingertip_errors_mm_);
    metrics["fingertip_error_mm"]["reachable_max"] = max_of(reachable_errors_mm_);
    metrics["gaze_error_deg"]["mean"] = freeplay::mean(gaze_errors_deg_);
    metrics["gaze_error_deg"]["max"] = max_of(gaze_errors_deg_);
    metrics["gaze_error_deg"]["unclamped_max"] = max_of(unclamped_gaze_errors_deg_);
    metrics["sync"]["error_mm_mean"] = freeplay::mean(sync_mean_mm_);
    metrics["sync"]["error_mm_max"] = max_of(sync_max_mm_);
    metrics["sync"]["lag_ms"] = freeplay::mean(sync_lag_ms_);
    metrics["joint_limit_margin_rad"] = limit_margin_;
    metrics["peak_velocity_fraction"] = peak_velocity_fraction_;
    metrics["peak_torque_fraction"] = dynamic_ ? peak_torque_fraction_ : kNaN;
    metrics["tracking_error_rad"]["rms"] = tracking_n_ > 0 ? std::sqrt(tracking_sq_ / static_cast<double>(tracking_n_)) : kNaN;
    metrics["tracking_error_rad"]["max"] = tracking_max_;
    metrics["self_collisions"]["count"] = collision_onsets_;
    metrics["self_collisions"]["time_s"] = collision_time_s_;
    metrics["settle_time_s"]["mean"] = freeplay::mean(settle_times_s_);
    metrics["settle_time_s"]["max"] = max_of(settle_times_s_);
    metrics["unsettled_targets"] = unsettled_;
    metrics["moves"]["succeeded"] = moves_succeeded_;
    metrics["moves"]["failed"] = moves_failed_;
    metrics["placement_error_mm"] = freeplay::mean(placement_errors_mm_);
    metrics["trace_hash"] = fmt::format("{:016x}", trace_.hash());
    auto record = provenance_fields(log_);
    record.update({{"kind", std::string(to_string(scenario::ScenarioKind::controller))},
                   {"duration_s", time()},
                   {"ended_by", "sequence"},
                   {"robot_mode", std::string(stage::to_string(spec_.mode))},
                   {"planner", scenario_.planner.name},
                   {"controller", {{"speed_fraction", spec_.speed_fraction},
                                   {"torque_fraction", spec_.torque_fraction},
                                   {"trace_interval_steps", spec_.trace_interval_steps},
                                   {"self_collision_pairs", collisions_.pairs()}}},
                   {"self_collisions", collisions_.hit()},
                   {"joint_limit_margin_joint", limit_margin_joint_},
                   {"peak_velocity_at", peak_velocity_at_},
                   {"peak_torque_at", peak_torque_at_},
                   {"trace_hash", fmt::format("{:016x}", trace_.hash())},
                   {"trace_checkpoints", trace_.checkpoints.size()},
                   {"trace_machine", trace_.machine},
                   {"targets", per_target_},
                   {"metrics", metrics}});
    return record;
  }

  const scenario::Scenario& scenario_;
  const ControllerSpec& spec_;
  SeedSequence seeds_;
  std::shared_ptr<const stage::StageModel> stage_model_;
  stage::Stage stage_;
  stage::NaoController nao_;
  sim::Sandtray tray_;
  stage::NaoSelfCollision collisions_;
  bool dynamic_ = true;
  std::vector<Target> targets_;
  NaoJointVector goal_{};
  NaoJointVector reference_{};
  NaoJointVector previous_q_{};
  NaoJointVector profile_speed_{};
  Eigen::Vector3d commanded_tip_ = Eigen::Vector3d::Zero();
  long steps_ = 0;
  long control_ticks_ = 0;
  // Moves.
  std::optional<MoveDriver> mover_;  // the one move driver (set in the constructor, once the Nao's reach is known)
  Follower follower_{*this};
  TraySink tray_sink_{*this};
  Vec2 last_finger_ = Vec2::Zero();
  bool released_ = false;
  // Output.
  EventLog log_;
  ControllerTrace trace_;
  std::vector<nlohmann::json> per_target_;
  std::vector<double> fingertip_errors_mm_;
  std::vector<double> reachable_errors_mm_;
  std::vector<double> gaze_errors_deg_;
  std::vector<double> unclamped_gaze_errors_deg_;
  std::vector<double> settle_times_s_;
  std::vector<double> placement_errors_mm_;
  std::vector<double> sync_mean_mm_;
  std::vector<double> sync_max_mm_;
  std::vector<double> sync_lag_ms_;
  int unsettled_ = 0;
  int moves_succeeded_ = 0;
  int moves_failed_ = 0;
  double limit_margin_ = std::numeric_limits<double>::infinity();
  std::string limit_margin_joint_;
  double peak_velocity_fraction_ = 0.0;
  double peak_torque_fraction_ = 0.0;
  std::string peak_velocity_at_;
  std::string peak_torque_at_;
  double tracking_sq_ = 0.0;
  long tracking_n_ = 0;
  double tracking_max_ = 0.0;
  int collision_onsets_ = 0;
  double collision_time_s_ = 0.0;
};

std::string number_list(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) out += ',';
    out += fmt::format("{}", v[i]);  // shortest round-trip representation
  }
  return out + "]";
}

}  // namespace

std::uint64_t ControllerTrace::hash() const {
  std::uint64_t h = fnv1a64(std::string_view{});
  for (const auto& c : checkpoints) {
    h = fnv1a64(std::string_view(reinterpret_cast<const char*>(&c.hash), sizeof c.hash), h);
  }
  return h;
}

std::string trace_machine_kind() {
#if defined(__x86_64__)
  const char* arch = "x86_64";
#elif defined(__aarch64__)
  const char* arch = "aarch64";
#else
  const char* arch = "unknown-arch";
#endif
#if defined(__clang__)
  const std::string compiler = fmt::format("clang-{}.{}", __clang_major__, __clang_minor__);
#elif defined(__GNUC__)
  const std::string compiler = fmt::format("gcc-{}.{}", __GNUC__, __GNUC_MINOR__);
#else
  const std::string compiler = "unknown-compiler";
#endif
  return fmt::format("{} {} mujoco-{}", arch, compiler, stage::mujoco_version_number());
}

ControllerEpisodeResult run_controller_episode(const scenario::Scenario& scenario, std::uint64_t seed,
                                               const SharedModels& models, const std::atomic<bool>& stop) {
  if (scenario.kind != scenario::ScenarioKind::controller) {
    throw InputError(fmt::format("scenario '{}' is of kind '{}'", scenario.name, to_string(scenario.kind)), "kind",
                     std::string(to_string(scenario::ScenarioKind::controller)));
  }
  ControllerEpisode episode(scenario, seed, models);
  return episode.run(stop);
}

EpisodeOutput run_controller_task(const EpisodeTask& task, const SharedModels& models, const std::atomic<bool>& stop) {
  auto result = run_controller_episode(task.variant->scenario, task.seed, models, stop);
  EpisodeOutput out;
  if (result.aborted) return out;
  const auto id = results::RunFolder::episode_file_id(task.variant->id, task.index);
  result.record["trace_file"] = "traces/" + id + ".jsonl";
  out.record = std::move(result.record);
  out.simulated_s = result.simulated_s;
  out.files["events/" + id + ".jsonl"] = result.events.to_jsonl();
  out.files["traces/" + id + ".jsonl"] = trace_jsonl(result.trace);
  return out;
}

std::string trace_jsonl(const ControllerTrace& trace) {
  nlohmann::json header{{"format", "freeplay-controller-trace"},
                        {"version", 1},
                        {"interval_steps", trace.interval_steps},
                        {"timestep_s", kPhysicsDtS},
                        {"machine", trace.machine},
                        {"checkpoints", trace.checkpoints.size()},
                        {"trace_hash", fmt::format("{:016x}", trace.hash())},
                        {"qpos_names", trace.qpos_names}};
  std::string out = header.dump() + "\n";
  for (const auto& c : trace.checkpoints) {
    out += fmt::format("{{\"step\":{},\"t\":{},\"hash\":\"{:016x}\",\"qpos\":{},\"qvel\":{}}}\n", c.step, c.time, c.hash,
                       number_list(c.qpos), number_list(c.qvel));
  }
  return out;
}

ControllerTrace parse_trace(const std::string& text, const std::string& file) {
  ControllerTrace trace;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
      if (!header) {
        if (j.value("format", "") != "freeplay-controller-trace") throw std::runtime_error("not a controller trace header");
        trace.interval_steps = j.at("interval_steps").get<int>();
        trace.machine = j.value("machine", "");
        trace.qpos_names = j.value("qpos_names", std::vector<std::string>{});
        header = true;
        continue;
      }
      TraceCheckpoint c;
      c.step = j.at("step").get<long>();
      c.time = j.at("t").get<double>();
      c.hash = std::stoull(j.at("hash").get<std::string>(), nullptr, 16);
      c.qpos = j.at("qpos").get<std::vector<double>>();
      c.qvel = j.at("qvel").get<std::vector<double>>();
      trace.checkpoints.push_back(std::move(c));
    } catch (const std::exception& e) {
      throw InputError(fmt::format("malformed trace line: {}", e.what()), "TRACE",
                       "a traces/<id>.jsonl file written by a controller episode", {file, line_number, 1});
    }
  }
  if (!header) {
    throw InputError("the trace file is empty", "TRACE", "a traces/<id>.jsonl file written by a controller episode",
                     {file, 1, 1});
  }
  return trace;
}

ControllerTrace load_trace(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("cannot read trace '{}'", path.string()), "TRACE", "a readable trace file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_trace(buffer.str(), path.string());
}

TraceDiff diff_traces(const ControllerTrace& a, const ControllerTrace& b, double tolerance) {
  TraceDiff diff;
  if (a.interval_steps != b.interval_steps) {
    diff.problem = fmt::format("checkpoint intervals differ: {} vs {} steps", a.interval_steps, b.interval_steps);
  } else if (a.checkpoints.size() != b.checkpoints.size()) {
    diff.problem = fmt::format("checkpoint counts differ: {} vs {}", a.checkpoints.size(), b.checkpoints.size());
  }
  const std::size_t n = std::min(a.checkpoints.size(), b.checkpoints.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& ca = a.checkpoints[i];
    const auto& cb = b.checkpoints[i];
    ++diff.compared;
    if (ca.hash != cb.hash && !diff.first_hash_mismatch) diff.first_hash_mismatch = i;
    if (ca.qpos.size() != cb.qpos.size() || ca.qvel.size() != cb.qvel.size()) {
      if (diff.problem.empty()) diff.problem = fmt::format("state sizes differ at checkpoint {}", i);
      break;
    }
    const auto scan = [&](const std::vector<double>& va, const std::vector<double>& vb, const char* field) {
      for (std::size_t k = 0; k < va.size(); ++k) {
        const double d = std::fabs(va[k] - vb[k]);
        const bool nan_mismatch = std::isnan(va[k]) != std::isnan(vb[k]);
        if (!(d <= diff.max_abs_diff) && !std::isnan(d)) {
          diff.max_abs_diff = d;
          const std::string name = std::string(field) == "qpos" && k < a.qpos_names.size() ? a.qpos_names[k] : "";
          diff.max_at = fmt::format("checkpoint {} (t {:.3f} s) {}[{}]{}", i, ca.time, field, k, name.empty() ? "" : " " + name);
        }
        if ((d > tolerance || nan_mismatch) && !diff.first_beyond) {
          diff.first_beyond = i;
          const std::string name = std::string(field) == "qpos" && k < a.qpos_names.size() ? a.qpos_names[k] : "";
          diff.first_beyond_at = fmt::format("checkpoint {} (t {:.3f} s) {}[{}]{}: {} vs {} (|Δ| {:.3g})", i, ca.time,
                                             field, k, name.empty() ? "" : " " + name, va[k], vb[k], d);
        }
      }
    };
    scan(ca.qpos, cb.qpos, "qpos");
    scan(ca.qvel, cb.qvel, "qvel");
  }
  diff.bit_identical = diff.problem.empty() && !diff.first_hash_mismatch && a.hash() == b.hash();
  diff.within_tolerance = diff.problem.empty() && !diff.first_beyond;
  return diff;
}

std::string trace_diff_text(const TraceDiff& diff, double tolerance) {
  std::string out;
  if (!diff.problem.empty()) out += fmt::format("structure: {}\n", diff.problem);
  out += fmt::format("{} checkpoints compared; {}\n", diff.compared,
                     diff.bit_identical ? "bit-identical"
                     : diff.first_hash_mismatch
                         ? fmt::format("first hash mismatch at checkpoint {}", *diff.first_hash_mismatch)
                         : "hashes equal");
  out += fmt::format("largest |Δ| {:.3g}{}\n", diff.max_abs_diff, diff.max_at.empty() ? "" : " at " + diff.max_at);
  if (diff.first_beyond) {
    out += fmt::format("first value beyond the tolerance {:g}: {}\n", tolerance, diff.first_beyond_at);
  }
  out += diff.within_tolerance ? fmt::format("within tolerance {:g}\n", tolerance)
                               : fmt::format("DIFFERENT beyond tolerance {:g}\n", tolerance);
  return out;
}

}  // namespace freeplay::runner
