#include "freeplay/runner/move_driver.hpp"

namespace freeplay::runner {

MoveDriver::MoveDriver(std::unique_ptr<planning::MoveExecutor> executor, Rng planner_rng)
    : executor_(std::move(executor)), planner_rng_(planner_rng) {}

std::optional<policies::ActionResult> MoveDriver::start(const policies::MoveItem& move, double t, MoveSink& sink) {
  std::optional<policies::ActionResult> previous;
  if (end_unreported_) {
    end_unreported_ = false;
    previous = finish(t, sink);
  } else if (moving()) {
    previous = cancel(t, sink);
  }
  executor_->start({move.item, move.target}, sink.move_world(), planner_rng_);
  end_unreported_ = !moving();
  move_ = move;
  sink.move_started(move, moving(), t);
  if (observer_ != nullptr) observer_->move_started(move, moving(), t);
  return previous;
}

std::optional<policies::ActionResult> MoveDriver::step(double t, MoveSink& sink) {
  if (end_unreported_) {
    end_unreported_ = false;
    return finish(t, sink);
  }
  if (!moving()) return std::nullopt;
  planning::MoveOutputs outputs;
  outputs.finger = [&](const planning::TimedPose& pose) {
    sink.finger(pose, t);
    if (observer_ != nullptr) observer_->finger(pose, t);
  };
  if (observer_ != nullptr) outputs.feedback = [&](int percentage) { observer_->progress(percentage); };
  outputs.arm = sink.arm();
  executor_->step(kMoveTickS, sink.move_world(), outputs);
  if (moving()) return std::nullopt;
  return finish(t, sink);
}

std::optional<policies::ActionResult> MoveDriver::cancel(double t, MoveSink& sink) {
  if (!moving()) return std::nullopt;
  executor_->cancel();
  return finish(t, sink);
}

policies::ActionResult MoveDriver::finish(double t, MoveSink& sink) {
  const auto& outcome = executor_->current();
  sink.move_ended(move_, outcome.status, move_result_event(outcome, move_.item), t);
  if (observer_ != nullptr) observer_->move_ended(move_, outcome, t);
  return move_action_result(outcome, move_.item);
}

events::MoveResult move_result_event(const planning::MoveOutcome& outcome, const std::string& item) {
  events::MoveResult e;
  e.item = item;
  e.status = std::string(planning::move_status_name(outcome.status));
  e.reason = outcome.reason();
  e.target_in_reach = outcome.target_in_reach;
  e.poses = outcome.poses_sent;
  if (outcome.plan.ok) {
    e.path_length_m = outcome.plan.metrics.path_length_m;
    e.min_clearance_mm = outcome.plan.metrics.min_clearance_m * 1000.0;
  }
  if (outcome.sync.samples > 0) {
    e.sync_error_mm_mean = outcome.sync.mean_error_m * 1000.0;
    e.sync_error_mm_max = outcome.sync.max_error_m * 1000.0;
    e.sync_lag_ms = outcome.sync.best_lag_s * 1000.0;
  }
  if (outcome.poses_sent > 0) e.duration_s = outcome.execution_duration_s;
  e.stolen_by_child = outcome.stolen_by_child;
  return e;
}

policies::ActionResult move_action_result(const planning::MoveOutcome& outcome, const std::string& item) {
  policies::ActionResult result;
  result.item = item;
  switch (outcome.status) {
    case planning::MoveStatus::Succeeded: result.kind = policies::ActionResult::Kind::MoveSucceeded; break;
    case planning::MoveStatus::Preempted: result.kind = policies::ActionResult::Kind::MoveCancelled; break;
    default:
      result.kind = policies::ActionResult::Kind::MoveFailed;
      result.reason = outcome.reason();
      break;
  }
  return result;
}

}  // namespace freeplay::runner
