// A front that brings both finger poses from outside and decisions in front of the robot side (as `freeplay serve
// --robot external` does): both act, the moves it asks for go through the episode's one move driver (their events
// are in the log as an in-process episode's) and a move observer hears each of them as the log records it.
#include <gtest/gtest.h>

#include <limits>

#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/robot_side.hpp"
#include "speaker_source.hpp"

using namespace freeplay;
using namespace freeplay::runner;

namespace {

scenario::Scenario child_robot_scenario() {
  return scenario::scenario_from_document(parse_yaml(
      "name: t\ncondition: child-robot\nprotocol: {greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 40, debriefing_s: 1}\n",
      "test.yaml"));
}

// Asks, once at free-play second 1, for the item nearest the robot's shoulder to be moved 4 cm towards it (within
// reach), and once at second 20 for an item that does not exist (reported, never driven).
class OneMove final : public policies::PlayPolicy {
 public:
  std::string name() const override { return "one-move"; }
  void reset(const policies::PolicyContext& /*context*/, Rng /*rng*/) override {}
  std::vector<policies::Action> decide(const policies::Observation& o) override {
    if (!asked_ && o.t >= 1.0 - 1e-9) {
      asked_ = true;
      const auto centre = o.self.arm_reach_centre;
      const policies::ItemObservation* nearest = nullptr;
      double best = std::numeric_limits<double>::infinity();
      for (const auto& seen : o.items) {
        const double d = (seen.pose.position() - centre).norm();
        if (d < best) best = d, nearest = &seen;
      }
      if (nearest == nullptr) return {};
      item = nearest->name;
      const Vec2 at = nearest->pose.position();
      return {policies::MoveItem{item, at + 0.04 * (centre - at).normalized()}};
    }
    if (!bad_asked_ && o.t >= 20.0 - 1e-9) {
      bad_asked_ = true;
      return {policies::MoveItem{"unicorn", {0.3, -0.1}}};
    }
    return {};
  }
  void on_result(const policies::ActionResult& result) override { results.push_back(result); }

  std::string item;
  std::vector<policies::ActionResult> results;

 private:
  bool asked_ = false;
  bool bad_asked_ = false;
};

// Hears the driver's moves (as the graph's move_sandbox_items server does).
class Listener final : public MoveObserver {
 public:
  void move_started(const policies::MoveItem& move, bool running, double /*t*/) override {
    started.push_back(move.item);
    (void)running;
  }
  void finger(const planning::TimedPose& /*pose*/, double /*t*/) override { ++poses; }
  void progress(int percentage) override { last_progress = percentage; }
  void move_ended(const policies::MoveItem& move, const planning::MoveOutcome& outcome, double /*t*/) override {
    ended.emplace_back(move.item, std::string(planning::move_status_name(outcome.status)));
  }

  std::vector<std::string> started;
  std::vector<std::pair<std::string, std::string>> ended;
  std::size_t poses = 0;
  int last_progress = -1;
};

}  // namespace

TEST(EpisodeExternalRobot, DecisionsBesidePosesFromOutsideMoveThroughTheOneDriverAndItsObserverHearsThem) {
  const auto s = child_robot_scenario();
  OneMove decisions;
  test::Speaker poses("Look at this!", "");  // the poses-from-outside side of the front
  Listener listener;
  const auto r = run_episode(
      {.scenario = s, .seed = 3, .id = "external", .decisions = &decisions, .robot = &poses, .moves = &listener});
  ASSERT_FALSE(decisions.item.empty());
  std::vector<const Event*> goals;
  std::vector<const Event*> results;
  bool said = false;
  for (const auto& e : r.events.events()) {
    if (e.source != "robot") continue;
    if (e.type() == "move_goal") goals.push_back(&e);
    if (e.type() == "move_result") results.push_back(&e);
    if (e.type() == "say" && e.data()["text"] == "Look at this!") said = true;
  }
  EXPECT_TRUE(said);  // the poses-from-outside side still acts
  // One move driven (the unknown item is reported to the decisions, never driven): in the log, heard by the observer.
  ASSERT_EQ(goals.size(), 1u);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(goals[0]->data()["item"], decisions.item);
  EXPECT_EQ(listener.started, std::vector<std::string>{decisions.item});
  ASSERT_EQ(listener.ended.size(), 1u);
  EXPECT_EQ(listener.ended[0].first, decisions.item);
  EXPECT_EQ(listener.ended[0].second, results[0]->data()["status"].get<std::string>());
  EXPECT_EQ(listener.poses, results[0]->data()["poses"].get<std::size_t>());
  EXPECT_EQ(results[0]->data()["status"], "succeeded");
  EXPECT_GT(listener.last_progress, 50);
  ASSERT_EQ(decisions.results.size(), 2u);
  EXPECT_EQ(decisions.results[0].kind, policies::ActionResult::Kind::MoveSucceeded);
  EXPECT_EQ(decisions.results[1].kind, policies::ActionResult::Kind::MoveFailed);
  EXPECT_EQ(decisions.results[1].item, "unicorn");
}

TEST(EpisodeExternalRobot, PosesFromOutsideAloneReplaceTheRobotSide) {
  const auto s = child_robot_scenario();
  test::Speaker poses("Look at this!", "");  // the poses-from-outside side of the front
  const auto r = run_episode({.scenario = s, .seed = 3, .id = "poses-only", .robot = &poses});
  for (const auto& e : r.events.events()) {
    EXPECT_FALSE(e.source == "robot" && (e.type() == "move_goal" || e.type() == "move_result")) << e.type();
  }
}
