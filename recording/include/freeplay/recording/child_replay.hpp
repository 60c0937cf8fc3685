#pragma once
// Re-runs a recorded session with the children's actions replayed open-loop from its bag while a (new) robot
// policy plays: touches (down / move / up at the recorded 10 Hz ticks), palette taps, gaze, speech and quitting.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "freeplay/agents/perception.hpp"
#include "freeplay/runner/child_action_source.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::recording {

/// What a recorded session's bag says about its scenario and its children's actions.
struct RecordedChildren {
  std::filesystem::path bag;                 ///< the bag read
  std::string scenario_yaml;                 ///< /freeplay/scenario: the validated scenario of the recorded episode
  std::string episode_id;                    ///< /freeplay/episode id
  std::uint64_t seed = 0;                    ///< the recorded episode's root seed
  double freeplay_duration_s = 0.0;          ///< free-play length (the recorded `freeplay_ended`)
  std::string ended_by;                      ///< "quit" | "cap"
  /// Per seat, per free-play tick (t = tick × 0.1 s), what the child did; ticks without actions are absent.
  std::map<std::string, std::map<long, agents::ChildActions>> actions;
  std::vector<std::string> seats;            ///< the children of the session, purple first
};

/// Reads the scenario and the children's actions from a session folder or bag; InputError naming the folder and
/// what is missing (no bag, an unindexed bag, no /freeplay/scenario: recorded by an older freeplay, no free play).
RecordedChildren read_recorded_children(const std::filesystem::path& session);

/// A ChildActionSource that plays the recorded actions back at their recorded ticks.
class ReplayedChildren final : public runner::ChildActionSource {
 public:
  /// Plays back `recording` (kept by reference: it must outlive this source).
  explicit ReplayedChildren(const RecordedChildren& recording) : recording_(recording) {}
  /// The recorded actions of `seat` at free-play time `t` (gaze and quitting as they stand then); past the
  /// recording, a child that has quit.
  agents::ChildActions actions(const std::string& seat, double t, double dt) override;

 private:
  const RecordedChildren& recording_;
};

/// The scenario of a replay: the recorded one with `policy` (empty: the recorded one; a different policy drops the
/// recorded policy parameters), free play capped at the recorded length, no cameras and no recording.
scenario::Scenario replay_scenario(const RecordedChildren& recording, const std::string& policy,
                                 const scenario::ScenarioVocabulary& vocabulary = {});

/// Runs the replay episode (the recorded seed, so the robot's random streams are the recorded ones); the record's
/// `label_share` metrics and the children's `quit_time_s` are removed (replayed children have no annotations) and
/// `replayed_from` names the bag.
runner::EpisodeResult replay_children(const RecordedChildren& recording, const scenario::Scenario& scenario,
                                      const runner::SharedModels& models);

}  // namespace freeplay::recording
