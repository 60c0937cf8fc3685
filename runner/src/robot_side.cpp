#include "freeplay/runner/robot_side.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "freeplay/core/error.hpp"

namespace freeplay::runner {

namespace {

constexpr double kTickS = 0.1;                           // the decision and `/poses` rate (10 Hz)
const Eigen::Vector3d kPurpleFace{0.30, -0.60, 0.25};   // seated on the long side below the screen
const Eigen::Vector3d kYellowFace{0.30, 0.265, 0.25};   // seated on the long side above it

int syllables_of(const std::string& text) {
  int count = 0;
  bool in_vowel = false;
  for (const char ch : text) {
    const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    const bool vowel = c == 'a' || c == 'e' || c == 'i' || c == 'o' || c == 'u' || c == 'y';
    if (vowel && !in_vowel) ++count;
    in_vowel = vowel;
  }
  return std::max(1, count);
}

}  // namespace

double speech_duration_s(const std::string& text) { return syllables_of(text) / kNaoSyllablesPerS; }

Eigen::Vector3d seat_face(const std::string& seat) { return seat == "yellow" ? kYellowFace : kPurpleFace; }

RobotSide::RobotSide(std::unique_ptr<policies::PlayPolicy> policy, std::unique_ptr<planning::MoveExecutor> executor,
                     Rng planner_rng, BadMove bad_move)
    : policy_(std::move(policy)), executor_(std::move(executor)), planner_rng_(planner_rng), bad_move_(bad_move) {}

void RobotSide::step(double t, policies::Observation& o, RobotWorld& world) {
  // The game said an item of ours was released: where it landed (the executor's placement error).
  if (!moving()) {
    for (const auto& message : o.interaction_events) {
      if (message.rfind("releasing_", 0) != 0) continue;
      if (const auto* item = o.item(message.substr(10)); item != nullptr && item->name == move_.item) {
        executor_->observe_release(item->pose.position());
      }
    }
  }
  o.self.moving_item = moving();
  o.self.current_item = move_.item;
  for (const auto& action : policy_->decide(o)) handle(action, t, world);
  if (move_unreported_) {
    move_unreported_ = false;
    finish_move(world, t);
  }
  if (moving()) {
    planning::MoveOutputs outputs;
    outputs.finger = [&](const planning::TimedPose& pose) { world.finger(pose, t); };
    outputs.arm = world.arm();
    executor_->step(kTickS, world.move_world(), outputs);
    if (!moving()) finish_move(world, t);
  }
  if (speech_pending_result_ && t >= speaking_until_) {
    speech_pending_result_ = false;
    policy_->on_result({policies::ActionResult::Kind::SpeechFinished, "", ""});
  }
}

void RobotSide::handle(const policies::Action& action, double t, RobotWorld& world) {
  if (const auto* move = std::get_if<policies::MoveItem>(&action)) {
    start_move(*move, t, world);
  } else if (const auto* look = std::get_if<policies::LookAt>(&action)) {
    world.look_at(*look, t);
  } else if (const auto* point = std::get_if<policies::PointAt>(&action)) {
    world.point_at(point->point, t);
  } else if (const auto* say = std::get_if<policies::Say>(&action)) {
    const double duration = speech_duration_s(say->text);
    speaking_until_ = t + duration;
    speech_pending_result_ = true;
    world.say(say->text, say->addressee, duration, t);
  } else if (std::holds_alternative<policies::CancelMove>(action)) {
    world.cancel(t);
    if (moving()) {
      executor_->cancel();
      finish_move(world, t);
    }
  }
}

void RobotSide::start_move(const policies::MoveItem& move, double t, RobotWorld& world) {
  const auto planning_world = world.move_world();
  const bool known = planning_world.item_centre && planning_world.item_centre(move.item).has_value();
  if (!std::isfinite(move.target.x()) || !std::isfinite(move.target.y()) || !known) {
    const auto problem = fmt::format("policy '{}' at free-play t = {:.1f} s asked to move '{}' to ({}, {})",
                                     policy_->name(), t, move.item, move.target.x(), move.target.y());
    if (bad_move_ == BadMove::Throw) throw InputError(problem, "MoveItem", "a known item and a finite target");
    spdlog::warn("{}: not executed", problem);
    ++counts_.moves_failed;
    policy_->on_result({policies::ActionResult::Kind::MoveFailed, move.item, "bad goal"});
    return;
  }
  executor_->start({move.item, move.target}, planning_world, planner_rng_);
  move_unreported_ = !moving();
  move_ = move;
  ++counts_.moves_started;
  world.move_started(move, moving(), t);
}

void RobotSide::finish_move(RobotWorld& world, double t) {
  const auto status = executor_->status();
  const auto& outcome = executor_->current();
  policies::ActionResult result;
  result.item = move_.item;
  nlohmann::json data{{"item", move_.item},
                      {"status", std::string(planning::move_status_name(status))},
                      {"reason", outcome.reason()},
                      {"target_in_reach", outcome.target_in_reach},
                      {"poses", outcome.poses_sent}};
  // The measurements go into the event too, so that a recording holds every metric (freeplay replay).
  if (outcome.plan.ok) {
    data["path_length_m"] = outcome.plan.metrics.path_length_m;
    data["min_clearance_mm"] = outcome.plan.metrics.min_clearance_m * 1000.0;
  }
  if (outcome.sync.samples > 0) {
    data["sync_error_mm_mean"] = outcome.sync.mean_error_m * 1000.0;
    data["sync_error_mm_max"] = outcome.sync.max_error_m * 1000.0;
    data["sync_lag_ms"] = outcome.sync.best_lag_s * 1000.0;
  }
  if (outcome.poses_sent > 0) data["duration_s"] = outcome.execution_duration_s;
  data["stolen_by_child"] = outcome.stolen_by_child;
  switch (status) {
    case planning::MoveStatus::Succeeded:
      result.kind = policies::ActionResult::Kind::MoveSucceeded;
      ++counts_.moves_succeeded;
      break;
    case planning::MoveStatus::Preempted:
      result.kind = policies::ActionResult::Kind::MoveCancelled;
      ++counts_.moves_cancelled;
      break;
    default:
      result.kind = policies::ActionResult::Kind::MoveFailed;
      result.reason = outcome.reason();
      ++counts_.moves_failed;
      break;
  }
  world.move_ended(move_, status, std::move(data), t);
  policy_->on_result(result);
}

}  // namespace freeplay::runner
