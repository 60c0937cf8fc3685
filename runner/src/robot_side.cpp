#include "freeplay/runner/robot_side.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "freeplay/core/error.hpp"

namespace freeplay::runner {

namespace {

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
    : owned_policy_(std::move(policy)), policy_(owned_policy_.get()), mover_(std::move(executor), planner_rng),
      bad_move_(bad_move) {}

RobotSide::RobotSide(policies::PlayPolicy& policy, std::unique_ptr<planning::MoveExecutor> executor, Rng planner_rng,
                     BadMove bad_move)
    : policy_(&policy), mover_(std::move(executor), planner_rng), bad_move_(bad_move) {}

void RobotSide::step(double t, policies::Observation& o, RobotWorld& world) {
  // The game said an item of ours was released: where it landed (the executor's placement error).
  if (!moving()) {
    for (const auto& message : o.interaction_events) {
      if (message.rfind("releasing_", 0) != 0) continue;
      if (const auto* item = o.item(message.substr(10)); item != nullptr && item->name == current_item()) {
        mover_.observe_release(item->pose.position());
      }
    }
  }
  o.self.moving_item = moving();
  o.self.current_item = current_item();
  for (const auto& action : policy_->decide(o)) handle(action, t, world);
  ended(mover_.step(t, world));
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
    ended(mover_.cancel(t, world));
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
  ended(mover_.start(move, t, world));
  ++counts_.moves_started;
}

void RobotSide::ended(const std::optional<policies::ActionResult>& result) {
  if (!result) return;
  switch (result->kind) {
    case policies::ActionResult::Kind::MoveSucceeded: ++counts_.moves_succeeded; break;
    case policies::ActionResult::Kind::MoveCancelled: ++counts_.moves_cancelled; break;
    default: ++counts_.moves_failed; break;
  }
  policy_->on_result(*result);
}

}  // namespace freeplay::runner
