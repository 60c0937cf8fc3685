#pragma once
// The robot side of an episode: what decides (the play policy, or an action source in front of it such as the web
// page's wizard and SPARC modes) and the one move driver (planner and move_sandbox_items executor, move_driver.hpp).
// It decides on a `policies::Observation` and acts through a `RobotWorld`: the simulated sandtray of an in-process
// episode, or a live ROS 1 graph (`freeplay robot`). The world side owns the body: the simulated Nao in process or
// under `freeplay serve`, the real one in the lab (it follows `/poses` as nao_behaviours does).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>

#include "freeplay/core/geometry.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/move_driver.hpp"

namespace freeplay::runner {

/// The Nao's text-to-speech articulation rate at its default speed (syllables per second).
inline constexpr double kNaoSyllablesPerS = 3.5;

/// Speaking time of `text` at the Nao's articulation rate (vowel groups counted as syllables).
double speech_duration_s(const std::string& text);

/// Where a seated child's face is approximately (sandtray frame, m): "purple" below the screen, "yellow" above.
Eigen::Vector3d seat_face(const std::string& seat);

/// What the robot side acts on: the world's actuators and, as a MoveSink, the view its moves plan on and the
/// finger poses they stream.
class RobotWorld : public MoveSink {
 public:
  /// A LookAt action (a point or a child's face).
  virtual void look_at(const policies::LookAt& look, double t) = 0;
  /// A PointAt action.
  virtual void point_at(const Vec2& point, double t) = 0;
  /// A Say action of `duration_s` seconds addressed to `to` ("" = both).
  virtual void say(const std::string& text, const std::string& to, double duration_s, double t) = 0;
  /// A CancelMove action (before the executor stops the move).
  virtual void cancel(double t) = 0;
};

/// How the robot side treats a MoveItem with an unknown item or a non-finite target.
enum class BadMove {
  Throw,   ///< a policy bug: InputError (in-process episodes)
  Report,  ///< logged and reported to the policy as MoveFailed (live graphs)
};

/// How the robot side's moves ended so far (a `freeplay robot` node's statistics). An episode's `planner` and
/// `executor` metrics are not counted here: EpisodeMetrics computes them from the move events.
struct RobotSideCounts {
  int moves_started = 0;    ///< MoveItem actions executed
  int moves_succeeded = 0;  ///< ended with the item at its target
  int moves_failed = 0;     ///< bad goals, refused, unplannable, aborted
  int moves_cancelled = 0;  ///< pre-empted by CancelMove
};

/// The robot's decisions: one policy (or action source), one move driver (one instance per episode or node).
class RobotSide {
 public:
  /// Takes the policy (already reset), the executor and the planner's random stream.
  RobotSide(std::unique_ptr<policies::PlayPolicy> policy, std::unique_ptr<planning::MoveExecutor> executor,
            Rng planner_rng, BadMove bad_move);
  /// Decides with `policy` (already reset; not owned, it must outlive the robot side): an action source in front
  /// of the robot, such as the web page's wizard.
  RobotSide(policies::PlayPolicy& policy, std::unique_ptr<planning::MoveExecutor> executor, Rng planner_rng,
            BadMove bad_move);

  /// One 10 Hz decision tick at `t` (s since free play started): completes `o.self` with the move state, lets the
  /// policy decide, acts through `world`, streams the running move's poses and reports ended actions.
  void step(double t, policies::Observation& o, RobotWorld& world);
  /// Lets `observer` (not owned; null: none) hear every move of its driver besides the world (MoveDriver).
  void set_move_observer(MoveObserver* observer) { mover_.set_observer(observer); }
  /// True when the policy uses perceived children (the world may skip perceiving them otherwise).
  bool perceives_children() const { return policy_->perceives_children(); }
  /// The policy's registered name.
  std::string policy_name() const { return policy_->name(); }
  /// True while a move streams poses.
  bool moving() const { return mover_.moving(); }
  /// The item of the current (or last) move.
  const std::string& current_item() const { return mover_.move().item; }
  /// True while an utterance started at or before `t` lasts.
  bool speaking(double t) const { return t < speaking_until_; }
  /// How its moves ended so far.
  const RobotSideCounts& counts() const { return counts_; }

 private:
  void handle(const policies::Action& action, double t, RobotWorld& world);
  void start_move(const policies::MoveItem& move, double t, RobotWorld& world);
  void ended(const std::optional<policies::ActionResult>& result);

  std::unique_ptr<policies::PlayPolicy> owned_policy_;  // null when the policy is an outside action source
  policies::PlayPolicy* policy_;
  MoveDriver mover_;
  BadMove bad_move_;
  double speaking_until_ = -1.0;   // s since free play started
  bool speech_pending_result_ = false;
  RobotSideCounts counts_;
};

}  // namespace freeplay::runner
