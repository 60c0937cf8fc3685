#pragma once
// The robot of a web session (`freeplay serve --web`): in `autonomous` mode the scenario's play policy drives it,
// in `wizard` mode only the experimenter's commands do (Wizard-of-Oz: a dropped item is moved through the planner
// and the move_sandbox_items executor, as the real woz_play), and in `supervised` mode (SPARC) the policy proposes
// its next action, which executes after a timeout unless the wizard vetoes or replaces it. Runs on the sim thread
// as the episode's RobotActionSource; commands arrive from any thread and are applied in order at the next tick.

#include <Eigen/Core>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "freeplay/core/event_log.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/robot_action_source.hpp"
#include "freeplay/runner/scenario.hpp"
#include "freeplay/web/commands.hpp"
#include "freeplay/web/robot_mode.hpp"
#include "freeplay/web/session_log.hpp"

namespace freeplay::web {

/// The robot of a web session: policy, wizard and SPARC supervision over one move executor.
class WizardRobot final : public runner::RobotActionSource {
 public:
  /// The scenario's policy (seeded from `seed`) in `mode`; proposals wait `sparc_timeout_s` (simulated seconds).
  WizardRobot(const runner::Scenario& scenario, std::uint64_t seed, SessionLog& log, RobotMode mode,
              double sparc_timeout_s);
  ~WizardRobot() override;

  /// Queues a validated robot command (any thread).
  void push(const Command& command);

  runner::RobotCommands commands(double t, const sim::Sandtray& tray, const runner::ReachDisc& reach) override;

  /// Hands over what the episode emitted and where the children's faces are (sim thread, after each tick).
  void observe(std::span<const Event> events, const std::map<std::string, Eigen::Vector3d>& faces);

  /// The robot's side of the state frame: mode, paused, move, pending proposal, last utterance (sim thread).
  nlohmann::json state() const;

 private:
  struct Proposal {
    int id = 0;
    std::vector<policies::Action> actions;
    double proposed_t = 0.0;  // free-play seconds
    double proposed_wall_s = 0.0;
  };
  struct Step;  // what one tick produces (finger poses, gaze and pointing targets)

  void apply(const Command& command, double t, const sim::Sandtray& tray, Step& step);
  void execute(const policies::Action& action, const std::string& source, const sim::Sandtray& tray, Step& step);
  void run_policy(double t, const sim::Sandtray& tray, Step& step);
  void decide_proposal(const std::string& decision, double t, const sim::Sandtray& tray, Step& step);
  void finish_move(const sim::Sandtray& tray);
  const policies::Observation& observation(double t, const sim::Sandtray& tray);
  void log(const sim::Sandtray& tray, const std::string& source, const std::string& type, nlohmann::json data);

  const runner::Scenario& scenario_;
  SessionLog& log_;
  RobotMode mode_;
  double sparc_timeout_s_;
  std::uint64_t seed_;
  std::unique_ptr<policies::PlayPolicy> policy_;
  std::unique_ptr<planning::MoveExecutor> executor_;
  Rng planner_rng_;
  std::mutex inbox_mutex_;
  std::deque<Command> inbox_;
  std::vector<std::string> interaction_events_;
  std::map<std::string, Eigen::Vector3d> faces_;
  policies::Observation observation_;
  std::optional<Proposal> proposal_;
  int next_proposal_id_ = 1;
  std::string move_source_;  // "wizard" | "policy" for the running move
  std::string move_item_;
  Vec2 move_target_ = Vec2::Zero();
  bool speech_pending_ = false;
  bool paused_ = false;  // the robot side is stopped: the policy is not consulted
  std::string last_said_;
  double last_t_ = 0.0;
};

}  // namespace freeplay::web
