#include <fmt/format.h>
#include <gtest/gtest.h>

#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/web/wizard_robot.hpp"
#include "session_support.hpp"

using namespace freeplay;
using namespace freeplay::web;

namespace {

runner::Scenario scenario(double cap_s) {
  const std::string text = fmt::format(
      "name: t\ncondition: child-robot\nrobot: {{policy: asocial}}\nprotocol: {{freeplay_cap_s: {}}}\n", cap_s);
  return test_session::scenario(text);
}

Command command(const std::string& body) {
  std::vector<std::string> names;
  for (const auto& item : runner::SharedModels::shipped().catalogue->items()) names.push_back(item.name);
  return parse_command(body, names);
}

// Hands the episode's events to the robot and lets a test act on the session log at every tick.
class Feed final : public runner::EpisodeObserver {
 public:
  Feed(WizardRobot& robot, std::function<void(const runner::EpisodeSnapshot&)> hook = {})
      : robot_(robot), hook_(std::move(hook)) {}
  void observe(const runner::EpisodeSnapshot& s) override {
    robot_.observe(s.new_events, {});
    if (hook_) hook_(s);
  }

 private:
  WizardRobot& robot_;
  std::function<void(const runner::EpisodeSnapshot&)> hook_;
};

std::vector<Event> of_type(const std::vector<Event>& events, const std::string& source, const std::string& type) {
  std::vector<Event> out;
  for (const auto& e : events) {
    if (e.source == source && e.type() == type) out.push_back(e);
  }
  return out;
}

struct Run {
  runner::EpisodeResult result;
  std::vector<Event> log;
  Pose2 zebra;  // where the zebra was when the first wizard move ended
};

Run run(RobotMode mode, const std::vector<std::string>& commands,
        const std::function<void(WizardRobot&, SessionLog&, const runner::EpisodeSnapshot&)>& hook = {}) {
  const auto s = scenario(30);
  SessionLog log;
  WizardRobot robot(s, 3, log, mode, 2.0);
  for (const auto& c : commands) robot.push(command(c));
  Run out;
  bool moved = false;
  runner::EpisodeObservers observers;
  observers.push_back(std::make_unique<Feed>(robot, [&](const runner::EpisodeSnapshot& snap) {
    if (snap.stage == "freeplay" && !moved && !of_type(log.all(), "wizard", "move_result").empty()) {
      moved = true;
      out.zebra = snap.tray->item("zebra").pose;
    }
    if (hook) hook(robot, log, snap);
  }));
  const std::atomic<bool> stop{false};
  out.result = runner::run_episode({.scenario = s, .seed = 3, .stop = stop, .id = "t", .robot = &robot},
                                   runner::observed_by(observers));
  out.log = log.all();
  return out;
}

}  // namespace

TEST(WizardRobot, AWizardMoveGoesThroughThePlannerAndTheExecutorToTheDropPoint) {
  // The drop comes 2 s into free play, as from a page (at tick 0 the items are still settling into the stash).
  const auto r = run(RobotMode::Wizard, {}, [](WizardRobot& robot, SessionLog&, const runner::EpisodeSnapshot& s) {
    if (s.stage == "freeplay" && std::abs(s.freeplay_t - 2.0) < 0.05) {
      robot.push(command(R"({"type":"move","item":"zebra","x":0.3,"y":-0.1})"));
    }
  });
  const auto results = of_type(r.log, "wizard", "move_result");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].data()["status"], "succeeded");
  EXPECT_EQ(of_type(r.log, "policy", "robot_action").size(), 0u);  // the policy does not act in wizard mode
  EXPECT_NEAR(r.zebra.x, 0.3, 0.01);
  EXPECT_NEAR(r.zebra.y, -0.1, 0.01);
}

TEST(WizardRobot, SameSeedAndCommandsGiveTheSameLogs) {
  const std::vector<std::string> commands = {R"({"type":"mode","mode":"supervised"})",
                                             R"({"type":"say","text":"Hello!"})"};
  const auto a = run(RobotMode::Autonomous, commands);
  const auto b = run(RobotMode::Autonomous, commands);
  EXPECT_EQ(a.result.events.to_jsonl(), b.result.events.to_jsonl());
  ASSERT_EQ(a.log.size(), b.log.size());
  for (std::size_t i = 0; i < a.log.size(); ++i) {
    auto x = a.log[i].to_json(), y = b.log[i].to_json();
    if (x["data"].contains("wall_latency_s")) x["data"].erase("wall_latency_s"), y["data"].erase("wall_latency_s");
    EXPECT_EQ(x, y) << i;
  }
}

TEST(WizardRobot, SupervisedProposalsExecuteAfterTheTimeoutUnlessVetoed) {
  const auto timed_out = run(RobotMode::Supervised, {});
  const auto proposals = of_type(timed_out.log, "sparc", "proposal");
  const auto decisions = of_type(timed_out.log, "sparc", "decision");
  ASSERT_GE(proposals.size(), 1u);
  ASSERT_GE(decisions.size(), 1u);
  EXPECT_EQ(decisions[0].data()["decision"], "timeout_executed");
  EXPECT_NEAR(decisions[0].data()["latency_s"].get<double>(), 2.0, 1e-6);
  EXPECT_GE(of_type(timed_out.log, "policy", "robot_action").size(), 1u);

  // The wizard vetoes every proposal as soon as it appears: the policy never acts.
  const auto vetoed = run(RobotMode::Supervised, {}, [](WizardRobot& robot, SessionLog&, const runner::EpisodeSnapshot&) {
    if (!robot.state()["proposal"].is_null()) robot.push(command(R"({"type":"sparc","decision":"veto"})"));
  });
  const auto vetoes = of_type(vetoed.log, "sparc", "decision");
  ASSERT_GE(vetoes.size(), 1u);
  for (const auto& d : vetoes) EXPECT_EQ(d.data()["decision"], "vetoed");
  EXPECT_EQ(of_type(vetoed.log, "policy", "robot_action").size(), 0u);
  EXPECT_LT(vetoes[0].data()["latency_s"].get<double>(), 0.25);
}
