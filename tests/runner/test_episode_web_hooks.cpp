// The hooks the web page uses: the coder's current labels in the snapshot, and an external robot's speech going the
// way of a policy's `say` (heard by the children, in the event log).
#include <gtest/gtest.h>

#include <set>

#include "freeplay/agents/labels.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/robot_side.hpp"
#include "speaker_source.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

Scenario test_scenario(const std::string& condition) {
  return scenario_from_document(parse_yaml(
      "name: t\ncondition: " + condition +
          "\nprotocol: {greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 60, debriefing_s: 1}\n",
      "test.yaml"));
}

// Keeps what a test needs of every snapshot.
class Keep final : public EpisodeObserver {
 public:
  struct Tick {
    std::string stage;
    double freeplay_t = 0.0;
    std::array<std::string, 3> coded;
    bool robot_speaking = false;
  };
  void observe(const EpisodeSnapshot& s) override {
    Tick t{std::string(s.stage), s.freeplay_t, {}, s.robot != nullptr && s.robot->speaking};
    for (std::size_t a = 0; a < 3; ++a) t.coded[a] = std::string(s.children[0].coded[a]);
    ticks_.push_back(std::move(t));
  }
  explicit Keep(std::vector<Tick>& ticks) : ticks_(ticks) {}

 private:
  std::vector<Tick>& ticks_;
};

}  // namespace

TEST(EpisodeWebHooks, TheSnapshotCarriesTheCodersCurrentLabelsFromFreePlayOn) {
  const auto s = test_scenario("child-child");
  std::vector<Keep::Tick> ticks;
  EpisodeObservers observers;
  observers.push_back(std::make_unique<Keep>(ticks));
  const std::atomic<bool> stop{false};
  const auto r = run_episode({.scenario = s, .seed = 11, .stop = stop, .id = "coded"}, observed_by(observers));
  ASSERT_FALSE(ticks.empty());
  std::set<std::string> seen;
  const Keep::Tick* last_freeplay = nullptr;
  for (const auto& t : ticks) {
    if (t.stage == "greeting" || t.stage == "tutorial") {
      EXPECT_TRUE(t.coded[0].empty() && t.coded[1].empty() && t.coded[2].empty());
      continue;
    }
    for (std::size_t a = 0; a < 3; ++a) {
      ASSERT_FALSE(t.coded[a].empty()) << t.stage << " " << t.freeplay_t;
      EXPECT_NE(agents::label_names(agents::kAxes[a]).find(t.coded[a]), std::string_view::npos) << t.coded[a];
    }
    seen.insert(t.coded[1]);
    if (t.stage == "freeplay") last_freeplay = &t;
  }
  EXPECT_GE(seen.size(), 2u);  // the social engagement label changes during the minute
  // The bouts in progress at the end are the annotation's last bouts.
  ASSERT_NE(last_freeplay, nullptr);
  const auto& purple = *r.annotations.purple;
  for (std::size_t a = 0; a < 3; ++a) {
    const agents::LabelInterval* last = nullptr;
    for (const auto& bout : purple) {
      if (bout.axis == agents::kAxes[a] && (last == nullptr || bout.start >= last->start)) last = &bout;
    }
    ASSERT_NE(last, nullptr);
    EXPECT_EQ(std::string(last->name()), last_freeplay->coded[a]) << agents::axis_name(agents::kAxes[a]);
  }
}

TEST(EpisodeWebHooks, TheSnapshotCarriesTheChildsHiddenStateAsItsOwnTimelineHasIt) {
  // Kept apart from what the cameras and the coder see: freeplay.Env offers it only as privileged information.
  const auto s = test_scenario("child-child");
  struct Hidden {
    std::string stage;
    std::array<std::string, 3> labels;
    double motivation = 0.0;
    bool wants_to_stop = false;
  };
  class KeepHidden final : public EpisodeObserver {
   public:
    explicit KeepHidden(std::vector<Hidden>& ticks) : ticks_(ticks) {}
    void observe(const EpisodeSnapshot& snapshot) override {
      const auto& h = snapshot.children[0].hidden;
      ticks_.push_back({std::string(snapshot.stage), {std::string(h.labels[0]), std::string(h.labels[1]),
                        std::string(h.labels[2])}, h.motivation, h.wants_to_stop});
    }

   private:
    std::vector<Hidden>& ticks_;
  };
  std::vector<Hidden> ticks;
  EpisodeObservers observers;
  observers.push_back(std::make_unique<KeepHidden>(ticks));
  const std::atomic<bool> stop{false};
  const auto r = run_episode({.scenario = s, .seed = 11, .stop = stop, .id = "hidden"}, observed_by(observers));
  const Hidden* last_freeplay = nullptr;
  for (const auto& t : ticks) {
    EXPECT_GE(t.motivation, 0.0);
    EXPECT_LE(t.motivation, 1.0);
    if (t.stage == "freeplay") last_freeplay = &t;
  }
  ASSERT_NE(last_freeplay, nullptr);
  // The child's own (internal) timeline ends in the labels the last free-play snapshot showed.
  for (std::size_t a = 0; a < 3; ++a) {
    const agents::LabelInterval* last = nullptr;
    for (const auto& bout : r.children.front().internal) {
      if (bout.axis == agents::kAxes[a] && (last == nullptr || bout.start >= last->start)) last = &bout;
    }
    ASSERT_NE(last, nullptr);
    EXPECT_EQ(std::string(last->name()), last_freeplay->labels[a]) << agents::axis_name(agents::kAxes[a]);
  }
  EXPECT_EQ(last_freeplay->wants_to_stop, r.children.front().quit_time_s >= 0.0);
}

TEST(EpisodeWebHooks, AnExternalRobotsSpeechIsTheRobotsSayHeardInTheRoom) {
  const auto s = test_scenario("child-robot");
  std::vector<Keep::Tick> ticks;
  EpisodeObservers observers;
  observers.push_back(std::make_unique<Keep>(ticks));
  const std::atomic<bool> stop{false};
  test::Speaker speaker("Shall we build a zoo together?", "purple");
  const auto r =
      run_episode({.scenario = s, .seed = 5, .stop = stop, .id = "say", .robot = &speaker}, observed_by(observers));
  const Event* said = nullptr;
  for (const auto& e : r.events.events()) {
    if (e.source == "robot" && e.type() == "say" && e.data()["text"] == "Shall we build a zoo together?") said = &e;
  }
  ASSERT_NE(said, nullptr);
  EXPECT_EQ(said->data()["to"], "purple");
  const double duration = speech_duration_s("Shall we build a zoo together?");
  EXPECT_DOUBLE_EQ(said->data()["duration_s"].get<double>(), duration);
  int speaking = 0;
  for (const auto& t : ticks) {
    if (t.stage == "freeplay" && t.freeplay_t > 2.05 && t.freeplay_t < 2.0 + duration - 0.05) {
      EXPECT_TRUE(t.robot_speaking) << t.freeplay_t;
      ++speaking;
    }
  }
  EXPECT_GT(speaking, 5);
}
