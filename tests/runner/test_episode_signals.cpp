// Signals from outside an episode (a live graph's `sandtray/signals/*`) applied to the simulated protocol.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <deque>

#include "freeplay/runner/episode.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

/// Hands out scripted signals at given polls (one poll per 10 Hz tick).
class ScriptedSignals final : public SignalSource {
 public:
  explicit ScriptedSignals(std::deque<std::pair<int, sim::Signal>> script) : script_(std::move(script)) {}
  std::vector<sim::Signal> take() override {
    std::vector<sim::Signal> out;
    while (!script_.empty() && script_.front().first <= poll_) {
      out.push_back(script_.front().second);
      script_.pop_front();
    }
    ++poll_;
    return out;
  }

 private:
  std::deque<std::pair<int, sim::Signal>> script_;
  int poll_ = 0;
};

Scenario long_greeting() {
  return scenario_from_document(parse_yaml(
      "name: t\ncondition: child-child\nprotocol: {greeting_s: 600, tutorial_s: 90, freeplay_cap_s: 600, "
      "debriefing_s: 5}\n",
      "test.yaml"));
}

}  // namespace

TEST(EpisodeSignals, StageSignalsMoveTheProtocolOnAndGameSignalsReachTheGame) {
  const auto s = long_greeting();
  // Poll 5 (0.5 s into the greeting): start free play, skipping the rest of the greeting and the tutorial; then
  // items to the stash 1.9 s into free play, and blank_interface 2.9 s into it.
  ScriptedSignals signals({{5, sim::Signal::StartFreeplay}, {25, sim::Signal::ItemsToStash},
                           {35, sim::Signal::BlankInterface}});
  const std::atomic<bool> stop{false};
  const auto r = run_episode({.scenario = s, .seed = 3, .stop = stop, .id = "signals", .signals = &signals});
  std::vector<std::string> stages;
  std::vector<std::string> received;
  bool stashed = false;
  double freeplay_at = -1.0;
  for (const auto& e : r.events.events()) {
    if (e.source == "protocol" && e.type() == "stage") stages.push_back(e.data()["stage"]);
    if (e.type() == "stage" && e.data()["stage"] == "freeplay") freeplay_at = e.t;
    if (e.type() == "signal_received") received.push_back(e.data()["name"]);
    if (e.type() == "signal" && e.data()["name"] == "items_to_stash") stashed = true;
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"greeting", "freeplay", "debriefing"}));
  EXPECT_EQ(received, (std::vector<std::string>{"start_freeplay", "items_to_stash", "blank_interface"}));
  EXPECT_TRUE(stashed);
  EXPECT_NEAR(freeplay_at, 0.5, 1e-9);
  EXPECT_EQ(r.record["ended_by"], "signal");
  EXPECT_NEAR(r.duration_s, 2.9, 1e-9);
  EXPECT_FALSE(r.hit_cap);
}

TEST(EpisodeSignals, WithoutSignalsTheEpisodeIsUnchanged) {
  const auto s = long_greeting();
  ScriptedSignals silent({});
  const std::atomic<bool> stop{false};
  const auto with_source = run_episode({.scenario = s, .seed = 4, .stop = stop, .id = "signals", .signals = &silent});
  const auto plain = run_episode({.scenario = s, .seed = 4, .stop = stop});
  EXPECT_EQ(with_source.events.to_jsonl(), plain.events.to_jsonl());
}
