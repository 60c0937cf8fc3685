// The robot in the simulated room: what it observes (TF, zones, touches, events, its perception of the child) and
// what its actuators do to the world (the game's `/poses`, the Nao's gaze, arm and voice as the children see them).

#include <cmath>

#include "freeplay/core/error.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "sim_world.hpp"

namespace freeplay::runner::detail {

namespace {

constexpr double kRobotRestAfterS = 30.0;  // nao_behaviours: arm to rest after 30 s without poses
constexpr double kGazeOnItemM = 0.03;      // a gaze point this close to an item's centre looks at the item

}  // namespace

policies::Observation& SimWorld::observe(double t, bool perceive_children) {
  policies::Observation& o = observation_;
  o.t = t;
  o.items.clear();
  for (const auto& item : current_items()) {
    policies::ItemObservation obs;
    obs.name = item.name;
    obs.pose = item.pose;
    obs.visible = item.visible;
    for (const auto& h : item.holders) {
      if (h.kind == sim::Holder::Kind::Robot) obs.held_by_robot = true;
      if (h.kind == sim::Holder::Kind::Finger) obs.touched_by_child = true;
    }
    o.items.push_back(std::move(obs));
  }
  if (observed_zones_version_ != seen_zones_version_) {
    o.zones = observation_zones_;
    observed_zones_version_ = seen_zones_version_;
  }
  o.touches.clear();
  tray_.touches(touches_);
  for (const auto& touch : touches_) o.touches.push_back({touch.finger, touch.position});
  o.children.clear();
  o.self = {};
  o.interaction_events = std::move(pending_interaction_events_);
  pending_interaction_events_.clear();
  if (perceive_children) {
    const auto& c = children_[0];
    ChildTruth truth;
    truth.seat = c.seat_name;
    truth.gaze = c.last.gaze.kind;
    truth.gaze_point = c.last.gaze.point;
    truth.speaking = c.speaking(t);
    truth.speech_to_partner = c.last.speech && c.last.speech->to == agents::Addressee::Partner;
    truth.seconds_since_touch = t - c.last_touch_t;
    for (const auto& touch : touches_) {
      if (c.owns_finger(touch.finger) && !touch.item.empty()) truth.moving_item = touch.item;
    }
    o.children.push_back(perception_->perceive(truth, t));
  }
  const auto disc = body_->reach();
  o.self.arm_reach_known = true;
  o.self.arm_reach_centre = disc.centre;
  o.self.arm_reach_radius = disc.radius;
  o.self.speaking = t < robot_speaking_until_;
  return o;
}

ReachDisc SimWorld::reach() const { return body_->reach(); }

planning::MoveWorld SimWorld::move_world() { return sandtray_move_world(tray_); }

void SimWorld::greet(const std::string& text) {
  const double duration = speech_duration_s(text);
  // Said in the greeting stage, minutes before free play: it is over before free play's clock starts, so the
  // children never hear it as a free-play comment (robot_speech_started_ stays before t = 0).
  robot_speaking_until_abs_ = now() + duration;
  log_.emit({now(), "robot", events::Say{text, "", duration}});
}

void SimWorld::move_started(const policies::MoveItem& move, bool running, double /*t*/) {
  robot_moving_ = running;
  log_.emit({now(), "robot", events::MoveGoal{move.item, move.target.x(), move.target.y()}});
  robot_gaze_ = {RobotGaze::Kind::Item, move.item};
}

void SimWorld::robot_finger(const Vec2& p, double t) {
  tray_.robot_pose(p);
  robot_finger_ = p;
  robot_gaze_point_ = {p.x(), p.y(), 0.0};
  last_pose_t_ = t;
}

void SimWorld::finger(const planning::TimedPose& pose, double t) { robot_finger(pose.position, t); }

void SimWorld::move_ended(const policies::MoveItem& /*move*/, planning::MoveStatus /*status*/,
                          events::MoveResult result, double /*t*/) {
  robot_moving_ = false;
  log_.emit({now(), "robot", std::move(result)});
  robot_gaze_ = {RobotGaze::Kind::Tray, ""};
}

void SimWorld::look_at_point(const Eigen::Vector3d& point) {
  robot_gaze_ = {RobotGaze::Kind::Tray, ""};
  for (const auto& item : current_items()) {
    if ((item.pose.position() - point.head<2>()).norm() < kGazeOnItemM) robot_gaze_ = {RobotGaze::Kind::Item, item.name};
  }
  body_->look_at(point);
  robot_gaze_point_ = point;
  events::LookAt look{std::nullopt, point.x(), point.y(), point.z(), std::nullopt};
  if (robot_gaze_.kind == RobotGaze::Kind::Item) look.item = robot_gaze_.target;  // the item looked at
  log_.emit({now(), "robot", std::move(look)});
}

void SimWorld::look_at(const policies::LookAt& look, double /*t*/) {
  if (look.child) {
    robot_gaze_ = {RobotGaze::Kind::Child, *look.child};
    robot_gaze_point_ = body_->child_face(*look.child);
    body_->look_at(robot_gaze_point_);
    log_.emit({now(), "robot", events::LookAt{*look.child, 0.0, 0.0, 0.0, std::nullopt}});
  } else if (look.point) {
    look_at_point(*look.point);
  }
}

void SimWorld::point_at(const Vec2& point, double t) {
  body_->point_at(point);
  last_pose_t_ = t;
  log_.emit({now(), "robot", events::PointAt{point.x(), point.y()}});
}

void SimWorld::say(const std::string& text, const std::string& to, double duration_s, double t) {
  robot_speech_started_ = t;
  robot_speaking_until_ = t + duration_s;
  robot_speaking_until_abs_ = now() + duration_s;
  log_.emit({now(), "robot", events::Say{text, to, duration_s}});
}

void SimWorld::cancel(double /*t*/) {
  log_.emit({now(), "robot", events::Cancel{}});
}

// `/poses` from outside reach the game and the Nao follows them (nao_behaviours); gaze and pointing move the Nao;
// speech goes the way of a policy's `say`.
void SimWorld::apply_external(const RobotCommands& commands, double t) {
  for (const auto& p : commands.finger) {
    robot_finger(p, t);
    body_->follow_finger(p);
  }
  if (commands.look_at) look_at_point(*commands.look_at);
  if (commands.point_at) point_at(*commands.point_at, t);
  for (const auto& u : commands.say) say(u.text, u.to, speech_duration_s(u.text), t);
}

void SimWorld::rest_when_idle(double t) {
  if (last_pose_t_ > -1e8 && t - last_pose_t_ > kRobotRestAfterS) {
    body_->rest();
    last_pose_t_ = -1e9;
  }
}

}  // namespace freeplay::runner::detail
