#pragma once
// What decides for the robot of a web session (`freeplay serve --web`): in `autonomous` mode the scenario's play
// policy, in `wizard` mode only the experimenter's commands (Wizard-of-Oz: a dropped item is moved as the real
// woz_play does), and in `supervised` mode (SPARC) the policy proposes its next action, which executes after a
// timeout unless the wizard vetoes or replaces it. An action source in front of the episode's one robot side
// (runner::RobotSide): the episode observes for it (perceived children included), moves through the one move driver
// and reports the results back. Commands arrive from any thread and are applied in order at the next decision tick.

#include <deque>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/policies/play_policy.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "freeplay/web/commands.hpp"
#include "freeplay/web/robot_mode.hpp"
#include "freeplay/web/session_log.hpp"

namespace freeplay::web {

/// The decisions of a web session's robot: the scenario's policy, the wizard's commands and SPARC supervision.
class WizardSource final : public policies::PlayPolicy {
 public:
  /// The scenario's policy in `mode`; proposals wait `sparc_timeout_s` (simulated seconds); logs to `log`.
  WizardSource(const scenario::Scenario& scenario, SessionLog& log, RobotMode mode, double sparc_timeout_s);
  ~WizardSource() override;

  /// Queues a validated robot command (any thread).
  void push(const Command& command);
  /// The game's clock after a tick (sim thread): the stamp of what it logs at the next decision tick.
  void clock(double tray_time) { now_ = tray_time; }
  /// The robot's side of the state frame: mode, paused, move, pending proposal, last utterance (sim thread).
  nlohmann::json state() const;

  /// "wizard" followed by the scenario policy's name.
  std::string name() const override;
  /// Resets the scenario's policy for the episode.
  void reset(const policies::PolicyContext& context, Rng rng) override;
  /// Applies the queued commands and, as the mode says, consults the policy; returns the actions to execute now.
  std::vector<policies::Action> decide(const policies::Observation& observation) override;
  /// Logs how a move ended and hands the policy the results of its own actions.
  void on_result(const policies::ActionResult& result) override;
  /// True when the scenario's policy perceives the children (the episode then perceives them for it).
  bool perceives_children() const override { return policy_->perceives_children(); }

 private:
  struct Proposal {
    int id = 0;
    std::vector<policies::Action> actions;
    double proposed_t = 0.0;  // free-play seconds
    double proposed_wall_s = 0.0;
  };
  struct Move {  // a move handed to the robot side, until its result
    std::string by;  // "wizard" | "policy"
    std::string item;
    Vec2 target = Vec2::Zero();
  };

  void apply(const Command& command, const policies::Observation& o);
  void execute(const policies::Action& action, const std::string& source);
  void run_policy(const policies::Observation& o);
  void decide_proposal(const std::string& decision, double t);
  void log(const std::string& source, const std::string& type, nlohmann::json data);

  SessionLog& log_;
  RobotMode mode_;
  double sparc_timeout_s_;
  std::unique_ptr<policies::PlayPolicy> policy_;
  std::mutex inbox_mutex_;
  std::deque<Command> inbox_;
  std::vector<policies::Action> out_;  // this tick's actions
  std::optional<Proposal> proposal_;
  int next_proposal_id_ = 1;
  std::deque<Move> moves_;       // started moves in order, until their results arrive
  bool speech_by_policy_ = false;  // the latest utterance was the policy's
  bool paused_ = false;            // the robot side is stopped: the policy is not consulted
  std::string last_said_;
  double now_ = 0.0;                // the game's clock (the log's stamps)
  double last_t_ = 0.0;             // free-play seconds of the last decision tick
  policies::RobotSelf self_;        // the robot's state at the last decision tick
};

}  // namespace freeplay::web
