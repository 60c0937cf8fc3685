#include "freeplay/web/wizard_robot.hpp"

#include <Eigen/Geometry>
#include <chrono>
#include <variant>

#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::web {

namespace {

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// An action as the event log and the page describe it.
nlohmann::json describe(const policies::Action& action) {
  if (const auto* move = std::get_if<policies::MoveItem>(&action)) {
    return {{"action", "move"}, {"item", move->item}, {"x", move->target.x()}, {"y", move->target.y()}};
  }
  if (const auto* look = std::get_if<policies::LookAt>(&action)) {
    if (look->child) return {{"action", "look_at"}, {"child", *look->child}};
    if (look->point) return {{"action", "look_at"}, {"x", look->point->x()}, {"y", look->point->y()}, {"z", look->point->z()}};
    return {{"action", "look_at"}};
  }
  if (const auto* point = std::get_if<policies::PointAt>(&action)) {
    return {{"action", "point_at"}, {"x", point->point.x()}, {"y", point->point.y()}};
  }
  if (const auto* say = std::get_if<policies::Say>(&action)) {
    return {{"action", "say"}, {"text", say->text}, {"to", say->addressee}};
  }
  if (const auto* wait = std::get_if<policies::Wait>(&action)) return {{"action", "wait"}, {"seconds", wait->seconds}};
  return {{"action", "stop"}};
}

}  // namespace

struct WizardRobot::Step {
  runner::RobotCommands out;
  planning::MoveWorld world;
};

WizardRobot::WizardRobot(const runner::Scenario& scenario, std::uint64_t seed, SessionLog& log, RobotMode mode,
                         double sparc_timeout_s)
    : scenario_(scenario), log_(log), mode_(mode), sparc_timeout_s_(sparc_timeout_s), seed_(seed),
      planner_rng_(SeedSequence(seed).seed_for("web.planner")) {
  policy_ = policies::make_policy(scenario.robot.policy, scenario.robot.params);
}

WizardRobot::~WizardRobot() = default;

void WizardRobot::push(const Command& command) {
  std::lock_guard lock(inbox_mutex_);
  inbox_.push_back(command);
}

void WizardRobot::observe(std::span<const Event> events, const std::map<std::string, Eigen::Vector3d>& faces) {
  for (const auto& e : events) {
    if (const auto* message = e.get<events::InteractionEvent>()) interaction_events_.push_back(message->message);
  }
  faces_ = faces;
}

void WizardRobot::log(const sim::Sandtray& tray, const std::string& source, const std::string& type,
                      nlohmann::json data) {
  log_.add({tray.time(), source, type, std::move(data)});
}

runner::RobotCommands WizardRobot::commands(double t, const sim::Sandtray& tray, const runner::ReachDisc& reach) {
  last_t_ = t;
  if (!executor_) {
    executor_ = runner::make_move_executor(scenario_, reach.centre, reach.radius);
    policies::PolicyContext context;
    for (const auto& item : tray.catalogue().items()) context.item_names.push_back(item.name);
    policy_->reset(context, SeedSequence(seed_).stream("web.policy"));
  }
  observation_.self.arm_reach_known = true;
  observation_.self.arm_reach_centre = reach.centre;
  observation_.self.arm_reach_radius = reach.radius;
  Step step{{}, runner::sandtray_move_world(tray)};
  std::deque<Command> inbox;
  {
    std::lock_guard lock(inbox_mutex_);
    inbox.swap(inbox_);
  }
  for (const auto& command : inbox) apply(command, t, tray, step);
  if (speech_pending_) {  // the policy's utterance is handed over; it hears it finished at the next tick
    speech_pending_ = false;
    policy_->on_result({policies::ActionResult::Kind::SpeechFinished, "", ""});
  }
  run_policy(t, tray, step);
  if (executor_->status() == planning::MoveStatus::Running) {
    planning::MoveOutputs outputs;
    outputs.finger = [&](const planning::TimedPose& pose) { step.out.finger.push_back(pose.position); };
    executor_->step(0.1, step.world, outputs);
    if (executor_->status() != planning::MoveStatus::Running) finish_move(tray);
  }
  return std::move(step.out);
}

void WizardRobot::apply(const Command& command, double t, const sim::Sandtray& tray, Step& step) {
  const auto& a = command.args;
  if (command.type == "mode") {
    const auto name = a["mode"].get<std::string>();
    if (!from_string(name, mode_)) mode_ = RobotMode::Wizard;  // validated by parse_command
    if (proposal_) decide_proposal("dropped", t, tray, step);
    log(tray, "wizard", "mode", {{"mode", name}});
    return;
  }
  if (command.type == "sparc_timeout") {
    sparc_timeout_s_ = a["seconds"].get<double>();
    log(tray, "wizard", "sparc_timeout", {{"seconds", sparc_timeout_s_}});
    return;
  }
  if (command.type == "component") {  // the robot side stopped: the policy is paused (and its running move cancelled)
    paused_ = a["action"] == "stop";
    if (proposal_) decide_proposal("dropped", t, tray, step);
    if (paused_ && move_source_ == "policy" && executor_->status() == planning::MoveStatus::Running) {
      executor_->cancel();
      finish_move(tray);
    }
    log(tray, "robot_side", paused_ ? "paused" : "resumed", {{"mode", std::string(to_string(mode_))}});
    return;
  }
  if (command.type == "sparc") {
    const auto decision = a["decision"].get<std::string>();
    if (!proposal_) {
      log(tray, "wizard", "sparc_ignored", {{"decision", decision}, {"reason", "no pending proposal"}});
      return;
    }
    decide_proposal(decision == "accept" ? "accepted" : "vetoed", t, tray, step);
    return;
  }
  // A robot action: the wizard's choice replaces a pending proposal.
  if (proposal_) decide_proposal("replaced", t, tray, step);
  policies::Action action;
  if (command.type == "move") {
    const auto item = a["item"].get<std::string>();
    Vec2 target(a["x"].get<double>(), a["y"].get<double>());
    if (a["frame"] == "item") {  // as woz_play: the drop point in the item's frame, brought to `sandtray` by its pose
      const auto pose = tray.item(item).pose;
      target = pose.position() + Eigen::Rotation2Dd(pose.theta) * target;
      if (!sim::on_screen(target)) {
        log(tray, "wizard", "move_refused", {{"item", item}, {"target", {target.x(), target.y()}},
                                             {"reason", "the drop point is off the screen"}});
        return;
      }
    }
    action = policies::MoveItem{item, target};
  } else if (command.type == "say") {
    action = policies::Say{a["text"].get<std::string>(), a["to"].get<std::string>()};
  } else if (command.type == "look_at") {
    policies::LookAt look;
    if (a.contains("child")) {
      look.child = a["child"].get<std::string>();
    } else if (a.contains("item")) {
      const auto p = tray.item(a["item"].get<std::string>()).pose.position();
      look.point = Eigen::Vector3d(p.x(), p.y(), 0.0);
    } else {
      look.point = Eigen::Vector3d(a["x"].get<double>(), a["y"].get<double>(), a["z"].get<double>());
    }
    action = look;
  } else if (command.type == "point_at") {
    action = policies::PointAt{a.contains("item") ? tray.item(a["item"].get<std::string>()).pose.position()
                                                  : Vec2(a["x"].get<double>(), a["y"].get<double>())};
  } else {
    action = policies::CancelMove{};
  }
  log(tray, "wizard", "command", {{"command", command.type}, {"args", a}});
  execute(action, "wizard", tray, step);
}

void WizardRobot::execute(const policies::Action& action, const std::string& source, const sim::Sandtray& tray,
                          Step& step) {
  auto data = describe(action);
  data["by"] = source;
  log(tray, source, "robot_action", data);
  if (const auto* move = std::get_if<policies::MoveItem>(&action)) {
    if (executor_->status() == planning::MoveStatus::Running) {
      executor_->cancel();
      finish_move(tray);
    }
    move_source_ = source;
    move_item_ = move->item;
    move_target_ = move->target;
    executor_->start({move->item, move->target}, step.world, planner_rng_);
    if (executor_->status() != planning::MoveStatus::Running) finish_move(tray);
  } else if (const auto* look = std::get_if<policies::LookAt>(&action)) {
    if (look->child) {
      const auto it = faces_.find(*look->child);
      if (it != faces_.end()) step.out.look_at = it->second;
    } else if (look->point) {
      step.out.look_at = *look->point;
    }
  } else if (const auto* point = std::get_if<policies::PointAt>(&action)) {
    step.out.point_at = point->point;
  } else if (const auto* say = std::get_if<policies::Say>(&action)) {  // heard and logged by the episode
    last_said_ = say->text;
    step.out.say.push_back({say->text, say->addressee});
    speech_pending_ = source != "wizard";
  } else if (std::holds_alternative<policies::CancelMove>(action)) {
    if (executor_->status() == planning::MoveStatus::Running) {
      executor_->cancel();
      finish_move(tray);
    }
  }
}

void WizardRobot::run_policy(double t, const sim::Sandtray& tray, Step& step) {
  if (mode_ == RobotMode::Wizard || paused_) {
    interaction_events_.clear();
    return;
  }
  if (mode_ == RobotMode::Supervised && proposal_) {
    if (t - proposal_->proposed_t >= sparc_timeout_s_ - 1e-9) decide_proposal("timeout_executed", t, tray, step);
    interaction_events_.clear();
    return;
  }
  auto actions = policy_->decide(observation(t, tray));
  std::erase_if(actions, [](const policies::Action& a) { return std::holds_alternative<policies::Wait>(a); });
  if (actions.empty()) return;
  if (mode_ == RobotMode::Autonomous) {
    for (const auto& action : actions) execute(action, "policy", tray, step);
    return;
  }
  proposal_ = Proposal{next_proposal_id_++, std::move(actions), t, wall_seconds()};
  nlohmann::json list = nlohmann::json::array();
  for (const auto& action : proposal_->actions) list.push_back(describe(action));
  log(tray, "sparc", "proposal", {{"id", proposal_->id}, {"actions", list}, {"timeout_s", sparc_timeout_s_}});
}

void WizardRobot::decide_proposal(const std::string& decision, double t, const sim::Sandtray& tray, Step& step) {
  auto proposal = std::move(*proposal_);
  proposal_.reset();
  log(tray, "sparc", "decision",
      {{"id", proposal.id}, {"decision", decision}, {"latency_s", t - proposal.proposed_t},
       {"wall_latency_s", wall_seconds() - proposal.proposed_wall_s}});
  if (decision == "accepted" || decision == "timeout_executed") {
    for (const auto& action : proposal.actions) execute(action, "policy", tray, step);
  }
}

void WizardRobot::finish_move(const sim::Sandtray& tray) {
  const auto& outcome = executor_->current();
  const auto status = outcome.status;
  nlohmann::json data{{"by", move_source_}, {"item", move_item_},
                      {"status", std::string(planning::move_status_name(status))},
                      {"target", {move_target_.x(), move_target_.y()}}};
  if (status != planning::MoveStatus::Succeeded) data["reason"] = outcome.reason() + ": " + outcome.message;
  log(tray, move_source_, "move_result", std::move(data));
  if (move_source_ == "policy") {
    policies::ActionResult result;
    result.item = move_item_;
    result.kind = status == planning::MoveStatus::Succeeded   ? policies::ActionResult::Kind::MoveSucceeded
                  : status == planning::MoveStatus::Preempted ? policies::ActionResult::Kind::MoveCancelled
                                                              : policies::ActionResult::Kind::MoveFailed;
    if (result.kind == policies::ActionResult::Kind::MoveFailed) result.reason = outcome.reason();
    policy_->on_result(result);
  }
}

const policies::Observation& WizardRobot::observation(double t, const sim::Sandtray& tray) {
  auto& o = observation_;
  o.t = t;
  o.items.clear();
  for (const auto& item : tray.items()) {
    policies::ItemObservation obs{item.name, item.pose, false, false, item.visible};
    for (const auto& h : item.holders) {
      obs.held_by_robot = obs.held_by_robot || h.kind == sim::Holder::Kind::Robot;
      obs.touched_by_child = obs.touched_by_child || h.kind == sim::Holder::Kind::Finger;
    }
    o.items.push_back(std::move(obs));
  }
  o.zones.clear();
  for (const auto& zone : tray.zones().zones()) o.zones.push_back({zone.colour, zone.polygon, zone.centroid});
  o.touches.clear();
  for (const auto& touch : tray.touches()) o.touches.push_back({touch.finger, touch.position});
  o.interaction_events = std::move(interaction_events_);
  interaction_events_.clear();
  o.self.moving_item = executor_->status() == planning::MoveStatus::Running;
  o.self.current_item = o.self.moving_item ? move_item_ : "";
  o.self.speaking = false;
  return o;
}

nlohmann::json WizardRobot::state() const {
  nlohmann::json out{{"mode", std::string(to_string(mode_))},
                     {"sparc_timeout_s", sparc_timeout_s_},
                     {"paused", paused_},
                     {"last_said", last_said_},
                     {"move", nullptr},
                     {"proposal", nullptr},
                     {"reach", nullptr}};
  if (observation_.self.arm_reach_known) {
    const auto& c = observation_.self.arm_reach_centre;
    out["reach"] = {{"centre", {c.x(), c.y()}}, {"radius", observation_.self.arm_reach_radius}};
  }
  if (executor_ && executor_->status() == planning::MoveStatus::Running) {
    out["move"] = {{"item", move_item_}, {"by", move_source_}, {"target", {move_target_.x(), move_target_.y()}}};
  }
  if (proposal_) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& action : proposal_->actions) list.push_back(describe(action));
    out["proposal"] = {{"id", proposal_->id}, {"actions", list},
                       {"remaining_s", std::max(0.0, proposal_->proposed_t + sparc_timeout_s_ - last_t_)}};
  }
  return out;
}

}  // namespace freeplay::web
