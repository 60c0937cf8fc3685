#pragma once
// The world side of an in-process episode (internal to freeplay_runner): the simulated sandtray, the synthetic
// children and the coder who watches them, the robot's presence in the room (its simulated body, gaze and voice as
// the children see them, the perception of the children it is given), the event log and the session metrics. The
// protocol loop (episode.cpp) drives it; the robot side (RobotSide) acts on it through RobotWorld.
//
// Its methods live in three files along their seams: sim_world.cpp (children, coder, snapshots),
// sim_world_robot.cpp (the robot in the room: observation, actuators, external commands) and sim_world_events.cpp
// (the game's events and the episode record). The metrics are results::EpisodeMetrics'
// (results/src/episode_metrics.cpp), fed the event log as replay feeds a recording.

#include <array>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/agents/child_agent.hpp"
#include "freeplay/agents/coder.hpp"
#include "freeplay/agents/perception.hpp"
#include "freeplay/agents/profile.hpp"
#include "freeplay/core/event_log.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/runner/child_action_source.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/perception_model.hpp"
#include "freeplay/runner/robot_action_source.hpp"
#include "freeplay/runner/robot_side.hpp"
#include "freeplay/results/episode_metrics.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::runner::detail {

/// The live sandtray as the metrics' world (sandtray_metrics_world.cpp).
class SandtrayMetricsWorld final : public results::MetricsWorld {
 public:
  /// Reads `tray` (not owned) when asked.
  explicit SandtrayMetricsWorld(const sim::Sandtray& tray) : tray_(tray) {}
  Vec2 item_position(const std::string& item) const override;
  std::string zone_at(const Vec2& p) const override;

 private:
  const sim::Sandtray& tray_;
};

inline constexpr double kTickS = kMoveTickS;  ///< the game's 10 Hz tick: one step of a driven move

/// One seated child: its agent and finger bookkeeping.
struct ChildSlot {
  std::string seat_name;                       ///< "purple" | "yellow"
  agents::Seat seat = agents::Seat::Bottom;    ///< where it sits
  int finger_offset = 0;                       ///< local fingers 1…3 → touch(offset+1 … offset+3)
  std::unique_ptr<agents::ChildAgent> agent;   ///< the synthetic child
  agents::ChildActions last;                   ///< its actions of the current tick
  std::array<bool, agents::kFingersPerChild + 1> down{};  ///< local finger on the screen
  double speaking_until = -1.0;                ///< free-play s
  double last_touch_t = -1e9;                  ///< free-play s of its last touch-down
  bool announced_quit = false;                 ///< `wants_to_stop` logged
  agents::GazeKind last_gaze_kind = agents::GazeKind::Away;  ///< last logged gaze
  int last_gaze_item = -1;                     ///< last logged gazed item

  /// True when global finger `finger` (1…6) is one of this child's.
  bool owns_finger(int finger) const { return finger > finger_offset && finger <= finger_offset + agents::kFingersPerChild; }
  /// True while an utterance lasts at free-play time `t`.
  bool speaking(double t) const { return t < speaking_until; }
};

/// What the robot is looking at, as the children see it.
struct RobotGaze {
  enum class Kind { Tray, Item, Child } kind = Kind::Tray;  ///< kind of target
  std::string target;                                      ///< item name or seat
};

/// The simulated world of one episode (see the file comment).
class SimWorld final : public RobotWorld {
 public:
  /// Seats the children of `scenario` (and, in child-robot scenarios, the robot's body and perception model).
  SimWorld(const scenario::Scenario& scenario, const SeedSequence& seeds, const SharedModels& models);
  ~SimWorld() override;

  // ---- protocol (episode.cpp) ----
  /// The game.
  sim::Sandtray& tray() { return tray_; }
  /// The event log.
  EventLog& log() { return log_; }
  /// True for a child-robot session.
  bool child_robot() const { return child_robot_; }
  /// Sandtray clock (s since the episode started).
  double now() const { return tray_.time(); }
  /// Free play starts now: remembers the bare map and starts the coder.
  void start_freeplay();
  /// Free play ended after `duration` s (`ended_by` "cap" | "quit"): logs it, measures the drawing and closes the
  /// children's and the coder's timelines.
  void finish_freeplay(double duration, const std::string& ended_by);
  /// True once free play should stop (the children want to stop).
  bool ended() const;
  /// Replaces the children's actions (a replayed session), or nullptr.
  void set_child_source(ChildActionSource* source) { child_source_ = source; }

  // ---- children and coder (sim_world.cpp) ----
  /// The children perceive the game and act at free-play time `t`.
  void step_children(double t);
  /// The coder's view of both players at `t`.
  void code_players(double t);
  /// Fills the ground-truth snapshot of this tick in protocol stage `stage` for observers (all but new_events).
  void snapshot(EpisodeSnapshot& out, std::string_view stage);
  /// The synthetic children, purple first.
  const std::vector<ChildSlot>& children() const { return children_; }
  /// The coder (after start_freeplay).
  agents::PairCoder& coder() { return *coder_; }

  // ---- the robot in the room (sim_world_robot.cpp) ----
  /// The robot's Observation at free-play time `t` (buffers reused every tick); perceives the child when asked.
  policies::Observation& observe(double t, bool perceive_children);
  /// The robot says `text` outside free play (greetings): heard and logged, not counted as an action.
  void greet(const std::string& text);
  /// Applies one tick of an external robot's commands (`freeplay serve --robot external`).
  void apply_external(const RobotCommands& commands, double t);
  /// The robot's arm-reach disc.
  ReachDisc reach() const;
  planning::MoveWorld move_world() override;
  planning::ArmFollower* arm() override;
  void move_started(const policies::MoveItem& move, bool running, double t) override;
  void finger(const planning::TimedPose& pose, double t) override;
  void move_ended(const policies::MoveItem& move, planning::MoveStatus status, events::MoveResult result,
                  double t) override;
  void look_at(const policies::LookAt& look, double t) override;
  void point_at(const Vec2& point, double t) override;
  void say(const std::string& text, const std::string& to, double duration_s, double t) override;
  void cancel(double t) override;
  /// The Nao's arm goes to rest after 30 s without poses (nao_behaviours).
  void rest_when_idle(double t);

  // ---- events and record (sim_world_events.cpp) ----
  /// Logs the game's new events and feeds the metrics every event logged since the last drain.
  void drain_tray_events();
  /// Mutual gaze and joint attention of this free-play tick (after its events were drained).
  void measure_gaze() { metrics_.measure_gaze(); }
  /// The episode record (metrics, children, provenance) for free play of `duration` s ended by `ended_by`.
  nlohmann::json record(double duration, const std::string& ended_by,
                        const agents::SessionAnnotations& annotations) const;

 private:
  class BodyFollower;
  void add_child(const std::string& seat_name, agents::Seat seat, int finger_offset, agents::ChildProfile profile,
                 Rng rng);
  void refresh_seen_zones();
  /// The tray's items in `items_`, refilled only when the tray has had an input since the last fill.
  const std::vector<sim::ItemState>& current_items();
  /// What child `me` sees this tick; `items` are the tray's items in tray order (current_items).
  void perceive(const ChildSlot& me, const std::vector<sim::ItemState>& items, double t,
                agents::ChildPerception& seen) const;
  void apply(ChildSlot& c, double t);
  Eigen::Vector3d face_of(const std::string& seat) const;
  Eigen::Vector3d gaze_point_of(const ChildSlot& c) const;
  void robot_finger(const Vec2& p, double t);
  void look_at_point(const Eigen::Vector3d& point);

  const scenario::Scenario& scenario_;
  const SharedModels& models_;
  sim::Sandtray tray_;
  bool child_robot_;
  EventLog log_;
  double freeplay_start_ = 0.0;
  std::vector<ChildSlot> children_;
  ChildActionSource* child_source_ = nullptr;  // replaces the agents' actions when set
  std::optional<agents::PairCoder> coder_;
  bool coded_robot_touching_ = false;
  int coded_robot_item_ = -1;
  std::array<agents::ChildPerception, 2> perceptions_{};
  std::vector<sim::ItemState> items_;    // the tray's items (current_items), reusing their storage
  std::vector<int> agent_item_;          // the children's index (agents::item_index) of each tray item, in tray order
  std::uint64_t items_input_count_ = ~std::uint64_t{0};  // the tray's input_count when items_ was filled
  std::vector<sim::TouchState> touches_;  // the tray's touches, refilled likewise
  std::array<agents::SeenZone, agents::kMaxSeenZones> seen_zones_{};
  int seen_zone_count_ = 0;
  std::uint64_t seen_zones_version_ = ~std::uint64_t{0};
  std::vector<policies::ZoneObservation> observation_zones_;
  policies::Observation observation_;                         // the robot's observation, reused every tick
  std::uint64_t observed_zones_version_ = ~std::uint64_t{0};  // seen_zones_version_ of observation_.zones
  // The robot in the room.
  std::unique_ptr<RobotBody> body_;
  std::unique_ptr<BodyFollower> follower_;
  std::unique_ptr<PerceptionModel> perception_;
  RobotGaze robot_gaze_;
  bool robot_moving_ = false;
  double robot_speech_started_ = -1.0;
  double robot_speaking_until_ = -1.0;
  double robot_speaking_until_abs_ = -1.0;
  double last_pose_t_ = -1e9;
  std::optional<Vec2> robot_finger_;
  Eigen::Vector3d robot_gaze_point_;
  std::vector<std::string> pending_interaction_events_;
  // Metrics.
  results::EpisodeMetrics metrics_{child_robot_};  // fed the event log at every drain of the tray's events
  cv::Mat freeplay_map_;           // the background published when free play started (the bare map)
  double drawing_coverage_ = 0.0;  // share of the map drawn over in the last background published in free play
  // Snapshots.
  std::vector<ChildSnapshot> snapshot_children_;
  RobotSnapshot robot_snapshot_;
};

}  // namespace freeplay::runner::detail
