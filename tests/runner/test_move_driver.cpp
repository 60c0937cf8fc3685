// The one move driver on a sink of our own: what it sends to the sink and what it returns when a move ends.
#include <gtest/gtest.h>

#include "freeplay/planning/plan.hpp"
#include "freeplay/runner/move_driver.hpp"
#include "one_ball_world.hpp"

namespace freeplay::runner {
namespace {

/// One item ("ball") on an empty table, dragged by the finger; records every call in order.
class BallSink final : public MoveSink {
 public:
  planning::MoveWorld move_world() override { return test::one_ball_world(ball, held); }
  void move_started(const policies::MoveItem& move, bool running, double) override {
    calls.push_back("started " + move.item + (running ? " running" : " refused"));
  }
  void finger(const planning::TimedPose& pose, double) override {
    ++poses;
    ball = pose.position;  // the game drags the item under the finger
  }
  void move_ended(const policies::MoveItem& move, planning::MoveStatus status, events::MoveResult result,
                  double) override {
    calls.push_back("ended " + move.item + " " + std::string(planning::move_status_name(status)));
    last_result = std::move(result);
  }

  Vec2 ball{0.20, -0.15};
  bool held = false;
  int poses = 0;
  std::vector<std::string> calls;
  events::MoveResult last_result;
};

/// Hears the driver's moves beside the sink (as a live graph's action server does); records every call in order.
class Listener final : public MoveObserver {
 public:
  void move_started(const policies::MoveItem& move, bool running, double) override {
    calls.push_back("started " + move.item + (running ? " running" : " refused"));
  }
  void finger(const planning::TimedPose& /*pose*/, double) override { ++poses; }
  void progress(int percentage) override { last_progress = percentage; }
  void move_ended(const policies::MoveItem& move, const planning::MoveOutcome& outcome, double) override {
    calls.push_back("ended " + move.item + " " + std::string(planning::move_status_name(outcome.status)));
    last_message = outcome.message;
  }

  int poses = 0;
  int last_progress = -1;
  std::vector<std::string> calls;
  std::string last_message;
};

MoveDriver make_driver(bool check_child_holding = false) {
  planning::MoveExecutorConfig config;
  config.check_child_holding = check_child_holding;
  return MoveDriver(std::make_unique<planning::MoveExecutor>(
                        std::shared_ptr<const planning::MotionPlanner>(planning::make_planner("astar")), config),
                    Rng(7));
}

// Steps until a move ends (at most `ticks`); returns its result.
std::optional<policies::ActionResult> run(MoveDriver& driver, BallSink& sink, int ticks) {
  for (int tick = 1; tick <= ticks; ++tick) {
    if (auto ended = driver.step(kMoveTickS * tick, sink)) return ended;
  }
  return std::nullopt;
}

TEST(MoveDriver, AMoveStreamsItsPosesThroughTheSinkAndEndsOnce) {
  auto driver = make_driver();
  BallSink sink;
  EXPECT_FALSE(driver.start({"ball", {0.40, -0.15}}, 0.0, sink).has_value());
  EXPECT_TRUE(driver.moving());
  const auto ended = run(driver, sink, 200);
  ASSERT_TRUE(ended.has_value());
  EXPECT_EQ(ended->kind, policies::ActionResult::Kind::MoveSucceeded);
  EXPECT_EQ(ended->item, "ball");
  EXPECT_EQ(sink.calls, (std::vector<std::string>{"started ball running", "ended ball succeeded"}));
  EXPECT_EQ(sink.poses, driver.outcome().poses_sent);
  EXPECT_NEAR(sink.ball.x(), 0.40, 1e-6);
  EXPECT_EQ(sink.last_result.status, "succeeded");
  EXPECT_EQ(sink.last_result.poses, static_cast<std::size_t>(sink.poses));
  EXPECT_TRUE(sink.last_result.path_length_m.has_value());
  EXPECT_FALSE(driver.step(100.0, sink).has_value());  // nothing more to report
}

TEST(MoveDriver, AMoveThatCannotStartEndsAtTheNextStep) {
  auto driver = make_driver(true);
  BallSink sink;
  sink.held = true;  // a child holds the ball: the executor refuses the goal
  driver.start({"ball", {0.40, -0.15}}, 0.0, sink);
  EXPECT_FALSE(driver.moving());
  EXPECT_EQ(sink.calls, std::vector<std::string>{"started ball refused"});
  const auto ended = driver.step(0.1, sink);
  ASSERT_TRUE(ended.has_value());
  EXPECT_EQ(ended->kind, policies::ActionResult::Kind::MoveFailed);
  EXPECT_EQ(ended->reason, driver.outcome().reason());
  EXPECT_EQ(sink.calls.back(), "ended ball aborted");
  EXPECT_EQ(sink.poses, 0);
}

TEST(MoveDriver, ANewMovePreemptsTheRunningOneAndCancelStopsIt) {
  auto driver = make_driver();
  BallSink sink;
  driver.start({"ball", {0.40, -0.15}}, 0.0, sink);
  run(driver, sink, 3);
  const auto preempted = driver.start({"ball", {0.30, -0.20}}, 0.4, sink);
  ASSERT_TRUE(preempted.has_value());
  EXPECT_EQ(preempted->kind, policies::ActionResult::Kind::MoveCancelled);
  EXPECT_TRUE(driver.moving());
  const auto cancelled = driver.cancel(0.5, sink);
  ASSERT_TRUE(cancelled.has_value());
  EXPECT_EQ(cancelled->kind, policies::ActionResult::Kind::MoveCancelled);
  EXPECT_FALSE(driver.cancel(0.6, sink).has_value());  // nothing runs any more
  EXPECT_EQ(sink.calls, (std::vector<std::string>{"started ball running", "ended ball preempted",
                                                  "started ball running", "ended ball preempted"}));
}

TEST(MoveDriver, AnObserverHearsEveryMoveAsTheSinkDoesWithItsFeedback) {
  auto driver = make_driver(true);
  BallSink sink;
  Listener listener;
  driver.set_observer(&listener);
  driver.start({"ball", {0.40, -0.15}}, 0.0, sink);
  ASSERT_TRUE(run(driver, sink, 200).has_value());
  sink.held = true;  // a child holds the ball: refused, ended at the next step
  driver.start({"ball", {0.20, -0.15}}, 30.0, sink);
  ASSERT_TRUE(driver.step(30.1, sink).has_value());
  EXPECT_EQ(listener.calls, sink.calls);
  EXPECT_EQ(listener.calls, (std::vector<std::string>{"started ball running", "ended ball succeeded",
                                                      "started ball refused", "ended ball aborted"}));
  EXPECT_EQ(listener.poses, sink.poses);
  EXPECT_GT(listener.last_progress, 50);  // the action's feedback: percent of the poses sent
  EXPECT_EQ(listener.last_message, driver.outcome().message);
  driver.set_observer(nullptr);  // a driver without an observer still runs its moves
  sink.held = false;
  driver.start({"ball", {0.25, -0.15}}, 40.0, sink);
  ASSERT_TRUE(run(driver, sink, 200).has_value());
  EXPECT_EQ(listener.calls.size(), 4u);
}

}  // namespace
}  // namespace freeplay::runner
