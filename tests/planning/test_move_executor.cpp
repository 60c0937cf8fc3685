// The move executor without physics: play_traj timing and feedback, speed, cancellation, child holds, bad goals,
// arm-reach flags, synchronisation metrics and determinism.

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "test_helpers.hpp"

namespace freeplay::planning {
namespace {

using testing::box;

/// A tray of named square items, with a settable "child holds it" flag; records what the executor sends.
struct FakeWorld {
  std::map<std::string, Vec2> centres{{"hippo", {0.10, -0.10}}, {"zebra", {0.40, -0.25}}};
  std::map<std::string, bool> held;
  std::vector<TimedPose> sent;
  std::vector<int> feedback;

  MoveWorld world() {
    MoveWorld w;
    w.item_centre = [this](const std::string& name) -> std::optional<Vec2> {
      const auto it = centres.find(name);
      if (it == centres.end()) return std::nullopt;
      return it->second;
    };
    w.footprints = [this] {
      std::vector<Obstacle> out;
      for (const auto& [name, c] : centres) out.push_back(box(name, c.x() - 0.02, c.x() + 0.02, c.y() - 0.02, c.y() + 0.02));
      return out;
    };
    w.held_by_child = [this](const std::string& name) { return held[name]; };
    return w;
  }

  MoveOutputs outputs(ArmFollower* arm = nullptr) {
    MoveOutputs o;
    o.finger = [this](const TimedPose& pose) { sent.push_back(pose); };
    o.feedback = [this](int percentage) { feedback.push_back(percentage); };
    o.arm = arm;
    return o;
  }
};

MoveExecutor make_executor(const std::string& planner = "astar", MoveExecutorConfig config = {}) {
  return MoveExecutor(std::shared_ptr<const MotionPlanner>(make_planner(planner)), config);
}

/// Steps until the move is no longer running; returns the number of steps taken.
int run_to_end(MoveExecutor& executor, FakeWorld& fake, double dt = 0.1, ArmFollower* arm = nullptr) {
  const MoveWorld world = fake.world();
  const MoveOutputs outputs = fake.outputs(arm);
  int steps = 0;
  while (executor.status() == MoveStatus::Running && steps < 100000) {
    executor.step(dt, world, outputs);
    ++steps;
  }
  return steps;
}

// A straight 10 cm move along x: A* visits 21 cells, one pose each, 5 mm apart.
const MoveGoal kStraightGoal{"hippo", {0.20, -0.10}};

TEST(MoveExecutor, StreamsPlayTrajPosesWithFeedbackAt10Hz) {
  FakeWorld fake;
  auto executor = make_executor();
  Rng rng(1);
  executor.start(kStraightGoal, fake.world(), rng);
  ASSERT_EQ(executor.status(), MoveStatus::Running);
  const std::size_t n = executor.current().poses.size();
  ASSERT_EQ(n, 21U);

  const MoveWorld world = fake.world();
  const MoveOutputs outputs = fake.outputs();
  for (std::size_t call = 0; call < n; ++call) {
    executor.step(0.1, world, outputs);
    ASSERT_EQ(fake.sent.size(), call + 1) << "one pose per 0.1 s step";
    EXPECT_NEAR(fake.sent.back().t, 0.1 * static_cast<double>(call), 1e-12);
  }
  EXPECT_EQ(executor.status(), MoveStatus::Succeeded);
  // Feedback i·100/N after poses 0..N−2, none after the last (play_traj).
  ASSERT_EQ(fake.feedback.size(), n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) EXPECT_EQ(fake.feedback[i], static_cast<int>(i * 100 / n));
  for (std::size_t i = 1; i < n; ++i) {
    EXPECT_NEAR((fake.sent[i].position - fake.sent[i - 1].position).norm(), 0.005, 1e-9);
  }
  EXPECT_NEAR((fake.sent.back().position - kStraightGoal.target).norm(), 0.0, 1e-9);
  const auto outcome = executor.outcome();
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->poses_sent, n);
  EXPECT_EQ(outcome->reason(), "none");
  EXPECT_NEAR(outcome->execution_duration_s, 0.1 * static_cast<double>(n - 1), 1e-12);
  EXPECT_NEAR(outcome->plan.metrics.path_length_m, 0.10, 1e-9);
  EXPECT_GT(outcome->plan.metrics.min_clearance_m, 0.0);
  EXPECT_EQ(executor.tally().succeeded, 1U);
  executor.step(0.1, world, outputs);  // a finished move sends nothing more
  EXPECT_EQ(fake.sent.size(), n);
}

TEST(MoveExecutor, FinerStepsDeliverEachPoseInTheStepCoveringItsStamp) {
  FakeWorld fake;
  auto executor = make_executor();
  Rng rng(1);
  executor.start(kStraightGoal, fake.world(), rng);
  const MoveWorld world = fake.world();
  const MoveOutputs outputs = fake.outputs();
  const double dt = 1.0 / 60.0;
  for (int k = 0; executor.status() == MoveStatus::Running; ++k) {
    const std::size_t before = fake.sent.size();
    executor.step(dt, world, outputs);
    for (std::size_t i = before; i < fake.sent.size(); ++i) {
      EXPECT_GE(fake.sent[i].t, k * dt - 1e-9);
      EXPECT_LT(fake.sent[i].t, (k + 1) * dt + 1e-9);
    }
    ASSERT_LE(fake.sent.size() - before, 1U);
  }
  EXPECT_EQ(fake.sent.size(), 21U);
}

TEST(MoveExecutor, SamplingPlannerPosesAreAtMost5mmApartByDefault) {
  FakeWorld fake;
  auto executor = make_executor("rrtconnect");
  Rng rng(3);
  executor.start({"hippo", {0.45, -0.05}}, fake.world(), rng);
  run_to_end(executor, fake);
  ASSERT_EQ(executor.status(), MoveStatus::Succeeded);
  ASSERT_GT(fake.sent.size(), 10U);
  for (std::size_t i = 1; i < fake.sent.size(); ++i) {
    EXPECT_LE((fake.sent[i].position - fake.sent[i - 1].position).norm(), 0.005 + 1e-9);
  }
}

TEST(MoveExecutor, FingerSpeedIsConfigurable) {
  FakeWorld fake;
  MoveExecutorConfig config;
  config.finger_speed_mps = 0.10;  // 1 cm per 0.1 s
  auto executor = make_executor("astar", config);
  Rng rng(1);
  executor.start({"hippo", {0.30, -0.10}}, fake.world(), rng);
  run_to_end(executor, fake);
  ASSERT_EQ(executor.status(), MoveStatus::Succeeded);
  ASSERT_EQ(fake.sent.size(), 21U);  // 20 cm at 1 cm per pose
  for (std::size_t i = 1; i < fake.sent.size(); ++i) {
    EXPECT_NEAR((fake.sent[i].position - fake.sent[i - 1].position).norm(), 0.010, 1e-9);
    EXPECT_NEAR(fake.sent[i].t - fake.sent[i - 1].t, 0.1, 1e-12);
  }
  EXPECT_NEAR((fake.sent.back().position - Vec2(0.30, -0.10)).norm(), 0.0, 1e-12);
}

TEST(MoveExecutor, ExactEndpointsReplaceTheAStarCellCorners) {
  for (const bool exact : {true, false}) {
    FakeWorld fake;
    fake.centres["hippo"] = {0.1023, -0.1017};
    MoveExecutorConfig config;
    config.exact_endpoints = exact;
    auto executor = make_executor("astar", config);
    Rng rng(1);
    executor.start({"hippo", {0.2031, -0.0988}}, fake.world(), rng);
    const auto& poses = executor.current().poses;
    ASSERT_GE(poses.size(), 2U);
    if (exact) {
      EXPECT_EQ(poses.front().position, Vec2(0.1023, -0.1017));
      EXPECT_EQ(poses.back().position, Vec2(0.2031, -0.0988));
    } else {  // the real path: corners of the start and goal cells
      EXPECT_NEAR((poses.front().position - Vec2(0.100, -0.100)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((poses.back().position - Vec2(0.200, -0.095)).norm(), 0.0, 1e-12);
    }
  }
}

TEST(RetimePath, ConstantSpacingAlongCornersEndingExactly) {
  const std::vector<TimedPose> path{{0.0, {0.0, 0.0}}, {0.1, {0.03, 0.0}}, {0.2, {0.03, 0.025}}};
  const auto out = retime_path(path, 0.1, 0.1);  // 1 cm spacing along 5.5 cm
  ASSERT_EQ(out.size(), 7U);
  EXPECT_NEAR((out[4].position - Vec2(0.03, 0.01)).norm(), 0.0, 1e-12);  // 4 cm of arc: around the corner
  EXPECT_NEAR((out.back().position - Vec2(0.03, 0.025)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(out.back().t, 0.6, 1e-12);
  EXPECT_THROW(retime_path(path, 0.0, 0.1), InputError);
  EXPECT_THROW(retime_path(path, 0.1, -1.0), InputError);
}

TEST(MoveExecutor, CancelStopsTheStreamAtOnce) {
  FakeWorld fake;
  auto executor = make_executor();
  Rng rng(1);
  executor.start(kStraightGoal, fake.world(), rng);
  const MoveWorld world = fake.world();
  const MoveOutputs outputs = fake.outputs();
  for (int i = 0; i < 7; ++i) executor.step(0.1, world, outputs);
  executor.cancel();
  EXPECT_EQ(executor.status(), MoveStatus::Preempted);
  for (int i = 0; i < 30; ++i) executor.step(0.1, world, outputs);
  EXPECT_EQ(fake.sent.size(), 7U);
  const auto outcome = executor.outcome();
  ASSERT_TRUE(outcome);
  EXPECT_EQ(outcome->failure, MoveFailure::Preempted);
  EXPECT_EQ(outcome->reason(), "preempted");
  EXPECT_NEAR(outcome->execution_duration_s, 0.6, 1e-12);
  EXPECT_EQ(executor.tally().preempted, 1U);
  executor.cancel();  // no effect once stopped
  EXPECT_EQ(executor.tally().preempted, 1U);
}

TEST(MoveExecutor, ANewGoalPreemptsTheRunningMove) {
  FakeWorld fake;
  auto executor = make_executor();
  Rng rng(1);
  executor.start(kStraightGoal, fake.world(), rng);
  const MoveWorld world = fake.world();
  const MoveOutputs outputs = fake.outputs();
  for (int i = 0; i < 3; ++i) executor.step(0.1, world, outputs);
  executor.start({"zebra", {0.40, -0.15}}, world, rng);
  EXPECT_EQ(executor.status(), MoveStatus::Running);
  EXPECT_EQ(executor.current().goal.item, "zebra");
  EXPECT_EQ(executor.tally().preempted, 1U);
  EXPECT_EQ(executor.tally().started, 2U);
}

TEST(MoveExecutor, RefusesAnItemAChildHoldsUnlessFaithful) {
  FakeWorld fake;
  fake.held["hippo"] = true;
  auto executor = make_executor();
  Rng rng(1);
  executor.start(kStraightGoal, fake.world(), rng);
  EXPECT_EQ(executor.status(), MoveStatus::Aborted);
  EXPECT_EQ(executor.current().failure, MoveFailure::ItemHeldByChild);
  EXPECT_EQ(executor.current().reason(), "item_held_by_child");
  run_to_end(executor, fake);
  EXPECT_TRUE(fake.sent.empty());
  EXPECT_EQ(executor.tally().refused_held, 1U);

  MoveExecutorConfig faithful;
  faithful.check_child_holding = false;  // the real server did not look
  auto real = make_executor("astar", faithful);
  real.start(kStraightGoal, fake.world(), rng);
  run_to_end(real, fake);
  EXPECT_EQ(real.status(), MoveStatus::Succeeded);
  EXPECT_FALSE(real.current().stolen_by_child);  // it was held before: nobody took it from the robot
  EXPECT_EQ(fake.sent.size(), 21U);
}

TEST(MoveExecutor, AChildGrabbingTheDraggedItemStopsTheMoveByDefault) {
  FakeWorld fake;
  auto executor = make_executor();
  Rng rng(1);
  executor.start(kStraightGoal, fake.world(), rng);
  const MoveWorld world = fake.world();
  const MoveOutputs outputs = fake.outputs();
  for (int i = 0; i < 5; ++i) executor.step(0.1, world, outputs);
  fake.held["hippo"] = true;
  executor.step(0.1, world, outputs);
  EXPECT_EQ(executor.status(), MoveStatus::Aborted);
  EXPECT_EQ(executor.current().failure, MoveFailure::StolenByChild);
  EXPECT_TRUE(executor.current().stolen_by_child);
  EXPECT_EQ(fake.sent.size(), 5U);
  EXPECT_EQ(executor.tally().stolen_by_child, 1U);

  FakeWorld again;
  MoveExecutorConfig keep;
  keep.on_steal = StealResponse::Continue;
  auto faithful = make_executor("astar", keep);
  faithful.start(kStraightGoal, again.world(), rng);
  const MoveWorld world2 = again.world();
  const MoveOutputs outputs2 = again.outputs();
  for (int i = 0; i < 5; ++i) faithful.step(0.1, world2, outputs2);
  again.held["hippo"] = true;
  run_to_end(faithful, again);
  EXPECT_EQ(faithful.status(), MoveStatus::Succeeded);
  EXPECT_TRUE(faithful.current().stolen_by_child);
  EXPECT_EQ(faithful.tally().stolen_by_child, 1U);
  EXPECT_EQ(again.sent.size(), 21U);
}

TEST(MoveExecutor, BadGoalsThrowAndChangeNothing) {
  FakeWorld fake;
  auto executor = make_executor();
  Rng rng(1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(executor.start({"hippo", {nan, -0.1}}, fake.world(), rng), InputError);
  EXPECT_THROW(executor.start({"hippo", {0.1, std::numeric_limits<double>::infinity()}}, fake.world(), rng),
               InputError);
  try {
    executor.start({"unicorn", {0.2, -0.1}}, fake.world(), rng);
    FAIL() << "an unknown item must throw";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "item");
    EXPECT_NE(error.allowed().find("hippo"), std::string::npos);
    EXPECT_NE(error.allowed().find("zebra"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("unicorn"), std::string::npos);
  }
  EXPECT_EQ(executor.status(), MoveStatus::Idle);
  EXPECT_EQ(executor.tally().started, 0U);

  // A bad goal does not pre-empt a running move either.
  executor.start(kStraightGoal, fake.world(), rng);
  const MoveWorld world = fake.world();
  executor.step(0.1, world, fake.outputs());
  EXPECT_THROW(executor.start({"unicorn", {0.2, -0.1}}, world, rng), InputError);
  EXPECT_EQ(executor.status(), MoveStatus::Running);
  EXPECT_EQ(executor.current().goal.item, "hippo");
  EXPECT_THROW(executor.step(-0.1, world, fake.outputs()), InputError);
  EXPECT_THROW(executor.step(0.1, world, MoveOutputs{}), InputError);
  MoveExecutorConfig no_budget;
  no_budget.time_budget_s = 0.0;
  EXPECT_THROW(make_executor("astar", no_budget), InputError);
  EXPECT_THROW(MoveExecutor(nullptr, MoveExecutorConfig{}), InputError);
}

TEST(MoveExecutor, PlanningFailuresAbortWithThePlannersReason) {
  FakeWorld fake;
  auto executor = make_executor();
  Rng rng(1);
  executor.start({"hippo", {0.7, -0.1}}, fake.world(), rng);
  EXPECT_EQ(executor.status(), MoveStatus::Aborted);
  EXPECT_EQ(executor.current().failure, MoveFailure::PlanningFailed);
  EXPECT_EQ(executor.current().reason(), "goal_off_screen");
  executor.start({"hippo", {0.40, -0.25}}, fake.world(), rng);  // zebra's centre
  EXPECT_EQ(executor.current().reason(), "goal_inside_obstacle");
  EXPECT_EQ(executor.tally().planning_failed, 2U);
  EXPECT_EQ(executor.current().poses_sent, 0U);
}

TEST(MoveExecutor, ReportsWhetherTheTargetIsInTheArmReachDisc) {
  FakeWorld fake;
  MoveExecutorConfig config;
  config.arm_reach = ArmReach{{0.30, 0.25}, 0.5, 0.3};  // disc radius 0.4 around (0.3, 0.25)
  auto executor = make_executor("astar", config);
  Rng rng(1);
  executor.start({"hippo", {0.30, -0.10}}, fake.world(), rng);  // 0.35 from the shoulder
  EXPECT_TRUE(executor.current().target_in_reach);
  EXPECT_FALSE(executor.current().start_in_reach);  // hippo at (0.1, −0.1): 0.403 away
  executor.start({"hippo", {0.30, -0.20}}, fake.world(), rng);  // 0.45 away: out of reach, moved anyway
  EXPECT_FALSE(executor.current().target_in_reach);
  EXPECT_EQ(executor.status(), MoveStatus::Running);
}

/// A fake arm whose fingertip shows the finger pose of `lag_ticks` poses earlier (the first pose before that).
class LaggingArm : public ArmFollower {
 public:
  explicit LaggingArm(std::size_t lag_ticks) : lag_(lag_ticks) {}
  FollowReport follow(const Vec2& finger, double /*t*/) override {
    history_.push_back(finger);
    const std::size_t i = history_.size() - 1;
    return {history_[i >= lag_ ? i - lag_ : 0], true};
  }

 private:
  std::size_t lag_;
  std::vector<Vec2> history_;
};

TEST(SyncMetrics, ALaggingArmIsMeasuredExactly) {
  for (const std::size_t lag : {0U, 1U, 3U, 7U}) {
    FakeWorld fake;
    auto executor = make_executor();
    Rng rng(1);
    LaggingArm arm(lag);
    executor.start(kStraightGoal, fake.world(), rng);
    run_to_end(executor, fake, 0.1, &arm);
    ASSERT_EQ(executor.status(), MoveStatus::Succeeded);
    const SyncMetrics& sync = executor.current().sync;
    const double lag_s = 0.1 * static_cast<double>(lag);
    EXPECT_EQ(sync.samples, 21U);
    EXPECT_EQ(sync.unreachable, 0U);
    EXPECT_NEAR(sync.best_lag_s, lag_s, 1e-9) << lag;
    EXPECT_NEAR(sync.error_at_best_lag_m, 0.0, 1e-12) << lag;
    EXPECT_NEAR(sync.max_lag_s, lag_s, 1e-9) << lag;
    EXPECT_NEAR(sync.max_error_m, 0.005 * static_cast<double>(lag), 1e-9) << lag;
    // Pose i is min(i, lag) poses behind: errors and lags average over the 21 poses.
    double expected_ticks = 0.0;
    for (std::size_t i = 0; i < 21; ++i) expected_ticks += static_cast<double>(std::min(i, lag));
    expected_ticks /= 21.0;
    EXPECT_NEAR(sync.mean_error_m, 0.005 * expected_ticks, 1e-9) << lag;
    EXPECT_NEAR(sync.mean_lag_s, 0.1 * expected_ticks, 1e-9) << lag;
  }
}

TEST(SyncMetrics, CountsUnreachablePosesAndChecksSizes) {
  const std::vector<TimedPose> finger{{0.0, {0.0, 0.0}}, {0.1, {0.01, 0.0}}};
  const std::vector<FollowReport> tips{{{0.0, 0.0}, true}, {{0.01, 0.002}, false}};
  const SyncMetrics sync = sync_metrics(finger, tips);
  EXPECT_EQ(sync.unreachable, 1U);
  EXPECT_NEAR(sync.max_error_m, 0.002, 1e-12);
  EXPECT_THROW(sync_metrics(finger, {tips[0]}), InputError);
}

TEST(MoveExecutor, SameSeedSamePoses) {
  const auto poses_for = [](std::uint64_t seed) {
    FakeWorld fake;
    auto executor = make_executor("rrtconnect");
    Rng rng(seed);
    executor.start({"hippo", {0.45, -0.05}}, fake.world(), rng);
    run_to_end(executor, fake);
    return fake.sent;
  };
  const auto a = poses_for(11);
  const auto b = poses_for(11);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].t, b[i].t);
    EXPECT_EQ(a[i].position, b[i].position);
  }
}

}  // namespace
}  // namespace freeplay::planning
