#pragma once
// The episode's metrics (the `metrics` of an episodes.jsonl record), computed in one place from the event log:
// the episode loop feeds it live and replay feeds it a recording, so both give the same numbers by construction.

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/core/event_log.hpp"
#include "freeplay/core/geometry.hpp"

namespace freeplay::results {

/// What the metrics read from the world at the tick being fed: item positions and the colour zone under a point.
class MetricsWorld {
 public:
  virtual ~MetricsWorld() = default;
  /// The item's position (sandtray frame, m).
  virtual Vec2 item_position(const std::string& item) const = 0;
  /// The colour of the zone under `p` (sandtray frame, m), "" when none.
  virtual std::string zone_at(const Vec2& p) const = 0;
};

/// Accumulates an episode's metrics from its events in emission order and its free-play ticks' gaze.
class EpisodeMetrics {
 public:
  /// `child_robot`: the purple child and the robot; otherwise the purple and yellow children.
  explicit EpisodeMetrics(bool child_robot);

  /// Feeds one event that the observers saw at sandtray time `tick` (the 10 Hz snapshot after the tray step).
  void observe(const Event& event, double tick, const MetricsWorld& world);
  /// Feeds the events of `log` not fed yet (this object remembers how far it read), all seen at `tick`.
  void observe_new(const EventLog& log, double tick, const MetricsWorld& world);
  /// Takes one free-play tick's gaze measurement (mutual gaze, joint attention) after that tick's events.
  void measure_gaze();

  /// The record's `metrics`: label shares of `annotations`, per-child and robot rates over `duration_s` of free
  /// play, `drawing_coverage` (measured on the tray's images by the caller), planner and executor figures.
  nlohmann::json to_json(double duration_s, const agents::SessionAnnotations& annotations, double drawing_coverage) const;

 private:
  struct Gaze {
    std::string kind = "away";  // a child's gaze name, or the robot's "tray" / "item" / "child"
    std::string target;         // item name or seat
  };
  struct ItemHistory {
    Vec2 grabbed_at = Vec2::Zero();
    std::string zone_at_grab;
    std::string last_mover;  // "purple", "yellow", "robot" or ""
    double last_move_t = -1e9;
  };

  std::string mover_of(const std::optional<int>& finger) const;
  void on_robot_event(const Event& e, double t);
  void on_grab(const events::ItemGrabbed& grab, double t, const MetricsWorld& world);
  void on_release(const events::ItemReleased& release, double t, const MetricsWorld& world);

  bool child_robot_;
  std::vector<std::string> seats_;
  std::size_t fed_ = 0;  // events of the live log already fed
  double freeplay_start_ = 0.0;
  bool in_freeplay_ = false;
  // Gaze.
  std::map<std::string, Gaze> children_gaze_;
  Gaze robot_gaze_{"tray", ""};
  bool joint_before_ = false;
  double mutual_gaze_s_ = 0.0;
  int joint_attention_episodes_ = 0;
  // Children and items.
  std::map<std::string, ItemHistory> history_;
  std::map<std::string, int> touches_;
  std::map<std::string, int> item_moves_;
  int zone_transitions_ = 0;
  int robot_item_moves_ = 0;
  int taken_by_robot_ = 0;
  int taken_by_child_ = 0;
  // Robot actions, planner and executor.
  std::map<std::string, int> actions_;
  double awaiting_response_since_ = -1.0;
  std::vector<double> response_latencies_;
  int moves_started_ = 0;
  int moves_succeeded_ = 0;
  int moves_failed_ = 0;
  int moves_cancelled_ = 0;
  int moves_stolen_ = 0;
  std::map<std::string, Vec2> move_targets_;       // item → target of its last move_goal
  std::map<std::string, Vec2> pending_placement_;  // item → target of its succeeded move, until released
  std::vector<double> path_lengths_m_, clearances_mm_, move_durations_s_, placement_errors_mm_, sync_mean_mm_,
      sync_lag_ms_;
  double sync_max_mm_ = 0.0;
};

}  // namespace freeplay::results
