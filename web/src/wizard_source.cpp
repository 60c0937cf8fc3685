#include "freeplay/web/wizard_source.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <variant>

#include "freeplay/sim/screen.hpp"

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

// The move status a result stands for (the executor's names).
std::string status_of(const policies::ActionResult& result) {
  switch (result.kind) {
    case policies::ActionResult::Kind::MoveSucceeded: return "succeeded";
    case policies::ActionResult::Kind::MoveCancelled: return "preempted";
    default: return "aborted";
  }
}

// Where item `name` is now (the robot's TF).
Vec2 item_position(const policies::Observation& o, const std::string& name) {
  const auto* item = o.item(name);
  return item != nullptr ? item->pose.position() : Vec2::Zero();
}

}  // namespace

WizardSource::WizardSource(const scenario::Scenario& scenario, SessionLog& log, RobotMode mode, double sparc_timeout_s)
    : log_(log), mode_(mode), sparc_timeout_s_(sparc_timeout_s),
      policy_(policies::make_policy(scenario.robot.policy, scenario.robot.params)) {}

WizardSource::~WizardSource() = default;

void WizardSource::push(const Command& command) {
  std::lock_guard lock(inbox_mutex_);
  inbox_.push_back(command);
}

std::string WizardSource::name() const { return "wizard+" + policy_->name(); }

void WizardSource::reset(const policies::PolicyContext& context, Rng rng) { policy_->reset(context, rng); }

void WizardSource::log(const std::string& source, const std::string& type, nlohmann::json data) {
  log_.add({now_, source, type, std::move(data)});
}

std::vector<policies::Action> WizardSource::decide(const policies::Observation& o) {
  last_t_ = o.t;
  self_ = o.self;
  out_.clear();
  std::deque<Command> inbox;
  {
    std::lock_guard lock(inbox_mutex_);
    inbox.swap(inbox_);
  }
  for (const auto& command : inbox) apply(command, o);
  run_policy(o);
  return std::move(out_);
}

void WizardSource::apply(const Command& command, const policies::Observation& o) {
  const auto& a = command.args;
  if (command.type == "mode") {
    const auto name = a["mode"].get<std::string>();
    if (!from_string(name, mode_)) mode_ = RobotMode::Wizard;  // validated by parse_command
    if (proposal_) decide_proposal("dropped", o.t);
    log("wizard", "mode", {{"mode", name}});
    return;
  }
  if (command.type == "sparc_timeout") {
    sparc_timeout_s_ = a["seconds"].get<double>();
    log("wizard", "sparc_timeout", {{"seconds", sparc_timeout_s_}});
    return;
  }
  if (command.type == "component") {  // the robot side stopped: the policy is paused (and its running move cancelled)
    paused_ = a["action"] == "stop";
    if (proposal_) decide_proposal("dropped", o.t);
    if (paused_ && !moves_.empty() && moves_.back().by == "policy") out_.push_back(policies::CancelMove{});
    log("robot_side", paused_ ? "paused" : "resumed", {{"mode", std::string(to_string(mode_))}});
    return;
  }
  if (command.type == "sparc") {
    const auto decision = a["decision"].get<std::string>();
    if (!proposal_) {
      log("wizard", "sparc_ignored", {{"decision", decision}, {"reason", "no pending proposal"}});
      return;
    }
    decide_proposal(decision == "accept" ? "accepted" : "vetoed", o.t);
    return;
  }
  // A robot action: the wizard's choice replaces a pending proposal.
  if (proposal_) decide_proposal("replaced", o.t);
  policies::Action action;
  if (command.type == "move") {
    const auto item = a["item"].get<std::string>();
    Vec2 target(a["x"].get<double>(), a["y"].get<double>());
    if (a["frame"] == "item") {  // as woz_play: the drop point in the item's frame, brought to `sandtray` by its pose
      const auto* seen = o.item(item);
      const Pose2 pose = seen != nullptr ? seen->pose : Pose2{};
      target = pose.position() + Eigen::Rotation2Dd(pose.theta) * target;
      if (!sim::on_screen(target)) {
        log("wizard", "move_refused", {{"item", item}, {"target", {target.x(), target.y()}},
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
      const auto p = item_position(o, a["item"].get<std::string>());
      look.point = Eigen::Vector3d(p.x(), p.y(), 0.0);
    } else {
      look.point = Eigen::Vector3d(a["x"].get<double>(), a["y"].get<double>(), a["z"].get<double>());
    }
    action = look;
  } else if (command.type == "point_at") {
    action = policies::PointAt{a.contains("item") ? item_position(o, a["item"].get<std::string>())
                                                  : Vec2(a["x"].get<double>(), a["y"].get<double>())};
  } else {
    action = policies::CancelMove{};
  }
  log("wizard", "command", {{"command", command.type}, {"args", a}});
  execute(action, "wizard");
}

void WizardSource::execute(const policies::Action& action, const std::string& source) {
  auto data = describe(action);
  data["by"] = source;
  log(source, "robot_action", data);
  if (const auto* move = std::get_if<policies::MoveItem>(&action)) {
    moves_.push_back({source, move->item, move->target});
  } else if (const auto* say = std::get_if<policies::Say>(&action)) {
    last_said_ = say->text;
    speech_by_policy_ = source == "policy";
  }
  out_.push_back(action);
}

void WizardSource::run_policy(const policies::Observation& o) {
  if (mode_ == RobotMode::Wizard || paused_) return;
  if (mode_ == RobotMode::Supervised && proposal_) {
    if (o.t - proposal_->proposed_t >= sparc_timeout_s_ - 1e-9) decide_proposal("timeout_executed", o.t);
    return;
  }
  auto actions = policy_->decide(o);
  std::erase_if(actions, [](const policies::Action& a) { return std::holds_alternative<policies::Wait>(a); });
  if (actions.empty()) return;
  if (mode_ == RobotMode::Autonomous) {
    for (const auto& action : actions) execute(action, "policy");
    return;
  }
  proposal_ = Proposal{next_proposal_id_++, std::move(actions), o.t, wall_seconds()};
  nlohmann::json list = nlohmann::json::array();
  for (const auto& action : proposal_->actions) list.push_back(describe(action));
  log("sparc", "proposal", {{"id", proposal_->id}, {"actions", list}, {"timeout_s", sparc_timeout_s_}});
}

void WizardSource::decide_proposal(const std::string& decision, double t) {
  auto proposal = std::move(*proposal_);
  proposal_.reset();
  log("sparc", "decision",
      {{"id", proposal.id}, {"decision", decision}, {"latency_s", t - proposal.proposed_t},
       {"wall_latency_s", wall_seconds() - proposal.proposed_wall_s}});
  if (decision == "accepted" || decision == "timeout_executed") {
    for (const auto& action : proposal.actions) execute(action, "policy");
  }
}

void WizardSource::on_result(const policies::ActionResult& result) {
  if (result.kind == policies::ActionResult::Kind::SpeechFinished) {
    if (speech_by_policy_) policy_->on_result(result);
    return;
  }
  if (moves_.empty()) return;  // not a move of ours (cannot happen: every move result follows a MoveItem)
  const Move move = moves_.front();
  moves_.pop_front();
  nlohmann::json data{{"by", move.by}, {"item", move.item}, {"status", status_of(result)},
                      {"target", {move.target.x(), move.target.y()}}};
  if (!result.reason.empty()) data["reason"] = result.reason;
  log(move.by, "move_result", std::move(data));
  if (move.by == "policy") policy_->on_result(result);
}

nlohmann::json WizardSource::state() const {
  nlohmann::json out{{"mode", std::string(to_string(mode_))},
                     {"sparc_timeout_s", sparc_timeout_s_},
                     {"paused", paused_},
                     {"last_said", last_said_},
                     {"move", nullptr},
                     {"proposal", nullptr},
                     {"reach", nullptr}};
  if (self_.arm_reach_known) {
    const auto& c = self_.arm_reach_centre;
    out["reach"] = {{"centre", {c.x(), c.y()}}, {"radius", self_.arm_reach_radius}};
  }
  if (!moves_.empty()) {
    const auto& m = moves_.back();
    out["move"] = {{"item", m.item}, {"by", m.by}, {"target", {m.target.x(), m.target.y()}}};
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
