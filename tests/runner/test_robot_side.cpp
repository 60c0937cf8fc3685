// The robot side on a world of our own: what it sends to the world, what the policy hears back.
#include <gtest/gtest.h>

#include <map>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/plan.hpp"
#include "freeplay/runner/robot_side.hpp"
#include "one_ball_world.hpp"

namespace freeplay::runner {
namespace {

/// Plays a fixed list of (tick, action) pairs and keeps the results it is told.
class ListPolicy final : public policies::PlayPolicy {
 public:
  explicit ListPolicy(std::map<int, policies::Action> actions) : actions_(std::move(actions)) {}
  std::string name() const override { return "list"; }
  void reset(const policies::PolicyContext&, Rng) override {}
  std::vector<policies::Action> decide(const policies::Observation& o) override {
    seen_moving.push_back(o.self.moving_item);
    const auto it = actions_.find(tick_++);
    if (it == actions_.end()) return {};
    return {it->second};
  }
  void on_result(const policies::ActionResult& result) override { results.push_back(result); }

  std::vector<policies::ActionResult> results;
  std::vector<bool> seen_moving;

 private:
  std::map<int, policies::Action> actions_;
  int tick_ = 0;
};

/// One item ("ball") on an empty table; records every call in order.
class RecordingWorld final : public RobotWorld {
 public:
  planning::MoveWorld move_world() override { return test::one_ball_world(ball, held); }
  void move_started(const policies::MoveItem& move, bool running, double) override {
    calls.push_back("move_started " + move.item + (running ? " running" : " refused"));
  }
  void finger(const planning::TimedPose& pose, double) override {
    ++poses;
    ball = pose.position;  // the game drags the item under the finger
  }
  void move_ended(const policies::MoveItem& move, planning::MoveStatus status, events::MoveResult result,
                  double) override {
    calls.push_back("move_ended " + move.item + " " + std::string(planning::move_status_name(status)));
    last_result = std::move(result);
  }
  void look_at(const policies::LookAt& look, double) override { calls.push_back("look_at " + look.child.value_or("")); }
  void point_at(const Vec2&, double) override { calls.push_back("point_at"); }
  void say(const std::string& text, const std::string&, double duration_s, double) override {
    calls.push_back("say " + text);
    said_duration = duration_s;
  }
  void cancel(double) override { calls.push_back("cancel"); }

  Vec2 ball{0.20, -0.15};
  bool held = false;
  int poses = 0;
  double said_duration = 0.0;
  std::vector<std::string> calls;
  events::MoveResult last_result;
};

RobotSide make_side(ListPolicy*& policy, std::map<int, policies::Action> actions, BadMove bad_move) {
  auto owned = std::make_unique<ListPolicy>(std::move(actions));
  policy = owned.get();
  auto executor = std::make_unique<planning::MoveExecutor>(
      std::shared_ptr<const planning::MotionPlanner>(planning::make_planner("astar")), planning::MoveExecutorConfig{});
  return RobotSide(std::move(owned), std::move(executor), Rng(7), bad_move);
}

void run(RobotSide& side, RecordingWorld& world, int ticks) {
  for (int tick = 0; tick < ticks; ++tick) {
    policies::Observation o;
    o.t = 0.1 * tick;
    side.step(o.t, o, world);
  }
}

TEST(RobotSide, AMoveStreamsPosesAndEndsWithItsMeasurements) {
  ListPolicy* policy = nullptr;
  auto side = make_side(policy, {{0, policies::MoveItem{"ball", {0.40, -0.15}}}}, BadMove::Throw);
  RecordingWorld world;
  run(side, world, 200);
  ASSERT_EQ(world.calls.size(), 2U);
  EXPECT_EQ(world.calls[0], "move_started ball running");
  EXPECT_EQ(world.calls[1], "move_ended ball succeeded");
  EXPECT_GT(world.poses, 3);
  EXPECT_GT(world.last_result.path_length_m.value_or(0.0), 0.15);
  ASSERT_EQ(policy->results.size(), 1U);
  EXPECT_EQ(policy->results[0].kind, policies::ActionResult::Kind::MoveSucceeded);
  EXPECT_TRUE(policy->seen_moving[1]);  // the policy sees its own move running
  EXPECT_EQ(side.counts().moves_started, 1);
  EXPECT_EQ(side.counts().moves_succeeded, 1);
}

TEST(RobotSide, CancelMoveEndsTheMoveAndTellsThePolicy) {
  ListPolicy* policy = nullptr;
  auto side = make_side(policy, {{0, policies::MoveItem{"ball", {0.40, -0.15}}}, {3, policies::CancelMove{}}},
                        BadMove::Throw);
  RecordingWorld world;
  run(side, world, 10);
  ASSERT_EQ(world.calls.size(), 3U);
  EXPECT_EQ(world.calls[1], "cancel");
  EXPECT_EQ(world.calls[2], "move_ended ball preempted");
  ASSERT_EQ(policy->results.size(), 1U);
  EXPECT_EQ(policy->results[0].kind, policies::ActionResult::Kind::MoveCancelled);
  EXPECT_EQ(side.counts().moves_cancelled, 1);
  EXPECT_FALSE(side.moving());
}

TEST(RobotSide, ABadMoveThrowsInProcessAndIsReportedOnAGraph) {
  ListPolicy* policy = nullptr;
  const std::map<int, policies::Action> bad{{0, policies::MoveItem{"unicorn", {0.40, -0.15}}},
                                            {1, policies::MoveItem{"ball", {std::nan(""), -0.15}}}};
  auto strict = make_side(policy, bad, BadMove::Throw);
  RecordingWorld world;
  EXPECT_THROW(run(strict, world, 1), InputError);
  auto lenient = make_side(policy, bad, BadMove::Report);
  run(lenient, world, 3);
  EXPECT_TRUE(world.calls.empty());  // nothing reached the world
  ASSERT_EQ(policy->results.size(), 2U);
  EXPECT_EQ(policy->results[0].kind, policies::ActionResult::Kind::MoveFailed);
  EXPECT_EQ(policy->results[1].kind, policies::ActionResult::Kind::MoveFailed);
  EXPECT_EQ(lenient.counts().moves_failed, 2);
}

TEST(RobotSide, SpeechFinishesAfterItsArticulationTime) {
  ListPolicy* policy = nullptr;
  auto side = make_side(policy, {{0, policies::Say{"Hello there", ""}}}, BadMove::Throw);
  RecordingWorld world;
  const double duration = speech_duration_s("Hello there");
  EXPECT_NEAR(duration, 4 / kNaoSyllablesPerS, 1e-12);  // he-llo the-re: four vowel groups
  run(side, world, 1);
  EXPECT_DOUBLE_EQ(world.said_duration, duration);
  EXPECT_TRUE(side.speaking(0.5));
  for (int tick = 1; tick < 20 && policy->results.empty(); ++tick) {
    policies::Observation o;
    o.t = 0.1 * tick;
    side.step(o.t, o, world);
    if (o.t < duration - 1e-9) {
      EXPECT_TRUE(policy->results.empty());
    }
  }
  ASSERT_EQ(policy->results.size(), 1U);
  EXPECT_EQ(policy->results[0].kind, policies::ActionResult::Kind::SpeechFinished);
}

}  // namespace
}  // namespace freeplay::runner
