#include <fmt/format.h>
#include <gtest/gtest.h>

#include <set>

#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/web/wizard_source.hpp"
#include "session_support.hpp"

using namespace freeplay;
using namespace freeplay::web;

namespace {

scenario::Scenario test_scenario(double cap_s, const std::string& policy = "asocial") {
  const std::string text = fmt::format(
      "name: t\ncondition: child-robot\nrobot: {{policy: {}}}\nprotocol: {{freeplay_cap_s: {}}}\n", policy, cap_s);
  scenario::ScenarioVocabulary vocabulary;
  vocabulary.policies = policies::policy_names();  // the shipped ones and this test's
  return scenario::scenario_from_document(parse_yaml(text, "test.yaml"), {}, vocabulary);
}

// A policy that perceives the children and counts the observations that held a perceived child.
class Perceiver final : public policies::PlayPolicy {
 public:
  explicit Perceiver(const YAML::Node& /*params*/) {}
  std::string name() const override { return "test_perceiver"; }
  void reset(const policies::PolicyContext& /*context*/, Rng /*rng*/) override {}
  std::vector<policies::Action> decide(const policies::Observation& o) override {
    ++decisions;
    for (const auto& child : o.children) seen_seats.insert(child.seat);
    return {};
  }
  bool perceives_children() const override { return true; }

  static inline int decisions = 0;
  static inline std::set<std::string> seen_seats;
};
FREEPLAY_REGISTER_POLICY(Perceiver, "test_perceiver", "test: perceives the children");

Command command(const std::string& body) {
  std::vector<std::string> names;
  for (const auto& item : runner::SharedModels::shipped().catalogue->items()) names.push_back(item.name);
  return parse_command(body, names);
}

// Hands the episode's events to the session log and the game's clock to the wizard, and lets a test act at every
// tick (as the web session's observer).
class Feed final : public runner::EpisodeObserver {
 public:
  Feed(WizardSource& robot, SessionLog& log, std::function<void(const runner::EpisodeSnapshot&)> hook = {})
      : robot_(robot), log_(log), hook_(std::move(hook)) {}
  void observe(const runner::EpisodeSnapshot& s) override {
    for (const auto& e : s.new_events) log_.add(e);
    robot_.clock(s.tray->time());
    if (hook_) hook_(s);
  }

 private:
  WizardSource& robot_;
  SessionLog& log_;
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
        const std::function<void(WizardSource&, SessionLog&, const runner::EpisodeSnapshot&)>& hook = {},
        const std::string& policy = "asocial") {
  const auto s = test_scenario(30, policy);
  SessionLog log;
  WizardSource robot(s, log, mode, 2.0);
  for (const auto& c : commands) robot.push(command(c));
  Run out;
  bool moved = false;
  runner::EpisodeObservers observers;
  observers.push_back(std::make_unique<Feed>(robot, log, [&](const runner::EpisodeSnapshot& snap) {
    if (snap.stage == "freeplay" && !moved && !of_type(log.all(), "wizard", "move_result").empty()) {
      moved = true;
      out.zebra = snap.tray->item("zebra").pose;
    }
    if (hook) hook(robot, log, snap);
  }));
  const std::atomic<bool> stop{false};
  out.result = runner::run_episode({.scenario = s, .seed = 3, .stop = stop, .id = "t", .decisions = &robot},
                                   runner::observed_by(observers));
  out.log = log.all();
  return out;
}

}  // namespace

TEST(WizardSource, AWizardMoveGoesThroughThePlannerAndTheExecutorToTheDropPoint) {
  // The drop comes 2 s into free play, as from a page (at tick 0 the items are still settling into the stash).
  const auto r = run(RobotMode::Wizard, {}, [](WizardSource& robot, SessionLog&, const runner::EpisodeSnapshot& s) {
    if (s.stage == "freeplay" && std::abs(s.freeplay_t - 2.0) < 0.05) {
      robot.push(command(R"({"type":"move","item":"zebra","x":0.3,"y":-0.1})"));
    }
  });
  const auto results = of_type(r.log, "wizard", "move_result");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].data()["status"], "succeeded");
  // The move is the episode's robot side's (the one move driver): its goal and result are the robot's events.
  const auto goals = of_type(r.result.events.events(), "robot", "move_goal");
  const auto ends = of_type(r.result.events.events(), "robot", "move_result");
  ASSERT_EQ(goals.size(), 1u);
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(goals[0].data()["item"], "zebra");
  EXPECT_EQ(ends[0].data()["status"], "succeeded");
  EXPECT_GT(ends[0].data()["poses"].get<int>(), 0);
  EXPECT_EQ(of_type(r.log, "policy", "robot_action").size(), 0u);  // the policy does not act in wizard mode
  EXPECT_NEAR(r.zebra.x, 0.3, 0.01);
  EXPECT_NEAR(r.zebra.y, -0.1, 0.01);
}

TEST(WizardSource, SameSeedAndCommandsGiveTheSameLogs) {
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

TEST(WizardSource, SupervisedProposalsExecuteAfterTheTimeoutUnlessVetoed) {
  const auto timed_out = run(RobotMode::Supervised, {});
  const auto proposals = of_type(timed_out.log, "sparc", "proposal");
  const auto decisions = of_type(timed_out.log, "sparc", "decision");
  ASSERT_GE(proposals.size(), 1u);
  ASSERT_GE(decisions.size(), 1u);
  EXPECT_EQ(decisions[0].data()["decision"], "timeout_executed");
  EXPECT_NEAR(decisions[0].data()["latency_s"].get<double>(), 2.0, 1e-6);
  EXPECT_GE(of_type(timed_out.log, "policy", "robot_action").size(), 1u);

  // The wizard vetoes every proposal as soon as it appears: the policy never acts.
  const auto vetoed = run(RobotMode::Supervised, {}, [](WizardSource& robot, SessionLog&, const runner::EpisodeSnapshot&) {
    if (!robot.state()["proposal"].is_null()) robot.push(command(R"({"type":"sparc","decision":"veto"})"));
  });
  const auto vetoes = of_type(vetoed.log, "sparc", "decision");
  ASSERT_GE(vetoes.size(), 1u);
  for (const auto& d : vetoes) EXPECT_EQ(d.data()["decision"], "vetoed");
  EXPECT_EQ(of_type(vetoed.log, "policy", "robot_action").size(), 0u);
  EXPECT_LT(vetoes[0].data()["latency_s"].get<double>(), 0.25);
}

TEST(WizardSource, AWebSessionPolicyThatPerceivesChildrenGetsThemInItsObservation) {
  Perceiver::decisions = 0;
  Perceiver::seen_seats.clear();
  run(RobotMode::Autonomous, {}, {}, "test_perceiver");
  EXPECT_GT(Perceiver::decisions, 100);  // 30 s of free play at 10 Hz
  EXPECT_EQ(Perceiver::seen_seats, std::set<std::string>{"purple"});
}

TEST(WizardSource, TheWizardsWordsAreSaidByTheOneRobotSide) {
  const auto r = run(RobotMode::Wizard, {R"({"type":"say","text":"Hi there","to":"purple"})"});
  const auto said = of_type(r.result.events.events(), "robot", "say");
  ASSERT_GE(said.size(), 2u);  // the greeting and the wizard's words, through the robot side
  EXPECT_EQ(said.back().data()["text"], "Hi there");
  EXPECT_EQ(of_type(r.log, "wizard", "robot_action").size(), 1u);
}
