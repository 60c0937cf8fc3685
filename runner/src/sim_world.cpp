#include "sim_world.hpp"

#include <algorithm>
#include <cmath>

#include "freeplay/agents/labels.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/sim/canvas.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::runner::detail {

namespace {

// Approximate faces for gaze targets (sandtray frame, m): the Nao's head above the yellow side, the experimenter
// standing behind the purple side (the children's seats: seat_face).
const Eigen::Vector3d kRobotHead{0.30, 0.20, 0.35};
const Eigen::Vector3d kExperimenter{-0.60, -0.90, 1.20};

agents::ChildProfile make_profile(const scenario::ChildSpec& spec, const agents::Population& population,
                                  const agents::ChildModelParams& params, Rng rng) {
  const auto base = spec.age ? agents::Population::fixed_age(*spec.age) : population;
  auto profile = base.sample(params.traits, rng);
  if (spec.age) profile.age_years = *spec.age;
  if (spec.gender) profile.gender = *spec.gender == "female" ? agents::Gender::Female : agents::Gender::Male;
  if (spec.sociability) profile.sociability = *spec.sociability;
  if (spec.assertiveness) profile.assertiveness = *spec.assertiveness;
  if (spec.attention_span) profile.attention_span = *spec.attention_span;
  if (spec.tablet_familiarity) profile.tablet = static_cast<agents::TabletFamiliarity>(*spec.tablet_familiarity);
  profile.validate();
  return profile;
}

agents::Population population_of(const scenario::Scenario& s) {
  switch (s.children.population) {
    case agents::PopulationName::pinsoro_cc: return agents::Population::pinsoro_child_child();
    case agents::PopulationName::pinsoro_cr: return agents::Population::pinsoro_child_robot();
    case agents::PopulationName::pinsoro: break;
  }
  return s.condition == scenario::Condition::ChildRobot ? agents::Population::pinsoro_child_robot()
                                      : agents::Population::pinsoro_child_child();
}

sim::SandtrayConfig tray_config() {
  sim::SandtrayConfig config;
  config.raster_width_px = 960;  // zones are segmented at 200 px anyway; half the raster cost
  return config;
}

}  // namespace

/// The robot body as the executor's arm follower (`nao_behaviours` following `/poses`).
class SimWorld::BodyFollower final : public planning::ArmFollower {
 public:
  explicit BodyFollower(RobotBody& body) : body_(body) {}
  planning::FollowReport follow(const Vec2& finger, double /*t*/) override {
    const auto reach = body_.reach();
    return {body_.follow_finger(finger), (finger - reach.centre).norm() < reach.radius};
  }

 private:
  RobotBody& body_;
};

SimWorld::SimWorld(const scenario::Scenario& scenario, const SeedSequence& seeds, const SharedModels& models)
    : scenario_(scenario), models_(models), tray_(models.catalogue, tray_config(), seeds.stream("sandtray")),
      child_robot_(scenario.condition == scenario::Condition::ChildRobot),
      robot_gaze_point_(sim::kScreenWidthM / 2, -sim::kScreenHeightM / 2, 0.0) {
  for (const auto& item : tray_.items()) agent_item_.push_back(agents::item_index(item.name));
  const auto& params = *models.child_params;
  const auto population = population_of(scenario);
  add_child("purple", agents::Seat::Bottom, 0,
            make_profile(scenario.children.purple, population, params, seeds.stream("profile.purple")),
            seeds.stream("child.purple"));
  if (!child_robot_) {
    add_child("yellow", agents::Seat::Top, agents::kFingersPerChild,
              make_profile(scenario.children.yellow, population, params, seeds.stream("profile.yellow")),
              seeds.stream("child.yellow"));
  } else {
    body_ = models.robot_body(scenario.robot.mode, scenario.robot.arm_reach_m);
    follower_ = std::make_unique<BodyFollower>(*body_);
    perception_ = std::make_unique<PerceptionModel>(scenario.perception, seeds.stream("perception"));
  }
}

SimWorld::~SimWorld() = default;

planning::ArmFollower* SimWorld::arm() { return follower_.get(); }

void SimWorld::add_child(const std::string& seat_name, agents::Seat seat, int finger_offset,
                         agents::ChildProfile profile, Rng rng) {
  ChildSlot c;
  c.seat_name = seat_name;
  c.seat = seat;
  c.finger_offset = finger_offset;
  c.agent = std::make_unique<agents::ChildAgent>(*models_.child_params, profile, seat,
                                                 rng);
  children_.push_back(std::move(c));
}

void SimWorld::start_freeplay() {
  freeplay_start_ = tray_.time();
  freeplay_map_ = tray_.background().clone();
  coder_.emplace(models_.child_params->coder, child_robot_);
}

void SimWorld::finish_freeplay(double duration, const std::string& ended_by) {
  drawing_coverage_ = sim::differing_pixel_share(tray_.background(), freeplay_map_);
  log_.emit({freeplay_start_ + duration, "protocol", events::FreeplayEnded{ended_by, duration}});
  for (auto& c : children_) c.agent->finish(duration);
  coder_->finish(duration);
}

bool SimWorld::ended() const {
  if (child_source_ != nullptr) {
    return std::all_of(children_.begin(), children_.end(), [](const ChildSlot& c) { return c.announced_quit; });
  }
  if (child_robot_) return children_[0].agent->wants_to_stop();
  return children_[0].agent->wants_to_stop() && children_[1].agent->wants_to_stop();
}

Eigen::Vector3d SimWorld::face_of(const std::string& seat) const {
  if (child_robot_ && seat == "purple") return body_->child_face(seat);
  return seat_face(seat);
}

Eigen::Vector3d SimWorld::gaze_point_of(const ChildSlot& c) const {
  const auto& g = c.last.gaze;
  switch (g.kind) {
    case agents::GazeKind::Tray:
    case agents::GazeKind::Item: return {g.point.x(), g.point.y(), 0.0};
    case agents::GazeKind::PartnerFace: return child_robot_ ? kRobotHead : face_of(c.seat_name == "purple" ? "yellow" : "purple");
    case agents::GazeKind::Robot: return kRobotHead;
    case agents::GazeKind::Experimenter: return kExperimenter;
    case agents::GazeKind::Away: break;
  }
  const auto face = face_of(c.seat_name);
  return {face.x() + 1.0, face.y(), face.z() + 0.3};  // looking aside, out of the table
}

void SimWorld::snapshot(EpisodeSnapshot& out, std::string_view stage) {
  const double t_abs = tray_.time();
  const bool started = stage == "freeplay" || stage == "debriefing";
  const double freeplay_t =
      t_abs - (started ? freeplay_start_ : scenario_.protocol.greeting_s + scenario_.protocol.tutorial_s);
  snapshot_children_.resize(children_.size());
  const auto touches = tray_.touches();
  for (std::size_t i = 0; i < children_.size(); ++i) {
    const auto& c = children_[i];
    auto& s = snapshot_children_[i];
    s.seat = c.seat_name;
    s.age_years = c.agent->profile().age_years;
    s.gender = std::string(agents::gender_name(c.agent->profile().gender));
    s.gaze = std::string(agents::gaze_kind_name(c.last.gaze.kind));
    s.gaze_point = gaze_point_of(c);
    s.head = face_of(c.seat_name);
    s.touches.clear();
    for (const auto& touch : touches) {
      if (c.owns_finger(touch.finger)) s.touches.emplace_back(touch.finger, touch.position);
    }
    s.speaking = stage == "freeplay" && c.speaking(freeplay_t);
    const auto& agent = *c.agent;
    for (std::size_t a = 0; a < agents::kAxisCount; ++a) {
      s.hidden.labels[a] = agents::label_name(agents::kAxes[a], agent.labels().index(agents::kAxes[a]));
    }
    s.hidden.motivation = agent.motivation();
    s.hidden.boredom = agent.boredom();
    s.hidden.answer_expectation = agent.answer_expectation();
    s.hidden.wants_to_stop = agent.wants_to_stop();
    s.coded = {};
    if (started && coder_) {
      for (std::size_t a = 0; a < agents::kAxisCount; ++a) {
        const auto axis = agents::kAxes[a];
        s.coded[a] = agents::label_name(axis, coder_->current(static_cast<int>(i), axis));
      }
    }
  }
  out.t = t_abs;
  out.freeplay_t = freeplay_t;
  out.stage = stage;
  out.tray = &tray_;
  out.children = snapshot_children_;
  out.robot = nullptr;
  if (child_robot_) {
    robot_snapshot_.joint_names.clear();
    robot_snapshot_.positions.clear();
    robot_snapshot_.velocities.clear();
    robot_snapshot_.efforts.clear();
    body_->joint_state(robot_snapshot_);
    robot_snapshot_.finger = robot_moving_ ? robot_finger_ : std::nullopt;
    robot_snapshot_.gaze_point = robot_gaze_point_;
    robot_snapshot_.speaking = t_abs < robot_speaking_until_abs_;
    out.robot = &robot_snapshot_;
  }
}

const std::vector<sim::ItemState>& SimWorld::current_items() {
  if (items_input_count_ != tray_.input_count()) {
    tray_.items(items_);
    items_input_count_ = tray_.input_count();
  }
  return items_;
}

void SimWorld::refresh_seen_zones() {
  if (seen_zones_version_ == tray_.background_version()) return;
  seen_zones_version_ = tray_.background_version();
  std::vector<const sim::Zone*> zones;
  for (const auto& z : tray_.zones().zones()) zones.push_back(&z);
  std::stable_sort(zones.begin(), zones.end(), [](const auto* a, const auto* b) { return a->area_m2 > b->area_m2; });
  seen_zone_count_ = 0;
  for (const auto* z : zones) {
    if (seen_zone_count_ >= static_cast<int>(agents::kMaxSeenZones)) break;
    const auto colour = sim::palette_from_name(z->colour);
    if (!colour) continue;
    auto& seen = seen_zones_[static_cast<std::size_t>(seen_zone_count_++)];
    seen.colour = *colour;
    seen.centroid = z->centroid;
    seen.radius_m = std::sqrt(std::max(z->area_m2, 1e-6) / 3.141592653589793);
  }
  observation_zones_.clear();
  for (const auto& z : tray_.zones().zones()) observation_zones_.push_back({z.colour, z.polygon, z.centroid});
}

void SimWorld::perceive(const ChildSlot& me, const std::vector<sim::ItemState>& items, double t,
                        agents::ChildPerception& seen) const {
  seen.item_count = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const auto& item = items[i];
    if (!item.visible || seen.item_count >= static_cast<int>(agents::kMaxSeenItems)) continue;
    const int index = agent_item_[i];
    if (index < 0) continue;
    auto& s = seen.items[static_cast<std::size_t>(seen.item_count++)];
    s.item = index;
    s.position = item.pose.position();
    s.in_stash = sim::in_stash(s.position);
    s.holder = agents::HolderView::Nobody;
    for (const auto& h : item.holders) {
      if (h.kind == sim::Holder::Kind::Robot) {
        if (s.holder == agents::HolderView::Nobody) s.holder = agents::HolderView::Robot;
      } else if (me.owns_finger(h.finger)) {
        s.holder = agents::HolderView::Me;
      } else if (s.holder != agents::HolderView::Me) {
        s.holder = agents::HolderView::Partner;
      }
    }
  }
  seen.zone_count = seen_zone_count_;
  std::copy_n(seen_zones_.begin(), seen_zone_count_, seen.zones.begin());
  seen.experimenter_present = true;
  auto& view = seen.partner;
  view = agents::PartnerView{};
  view.present = true;
  if (!child_robot_) {
    const ChildSlot& other = children_[&me == &children_[0] ? 1 : 0];
    for (const auto& touch : touches_) {
      if (!other.owns_finger(touch.finger) || view.touch_count >= 6) continue;
      view.touches[static_cast<std::size_t>(view.touch_count++)] = {touch.position, agents::item_index(touch.item)};
    }
    view.gaze = other.last.gaze;
    view.speech = other.last.speech;
    view.speaking = other.speaking(t);
    return;
  }
  view.is_robot = true;
  if (const auto hand = tray_.robot_hand()) {
    const auto item = tray_.robot_item();
    view.touches[0] = {*hand, item ? agents::item_index(*item) : -1};
    view.touch_count = 1;
  }
  switch (robot_gaze_.kind) {
    case RobotGaze::Kind::Child:
      view.gaze.kind = robot_gaze_.target == me.seat_name ? agents::GazeKind::PartnerFace : agents::GazeKind::Away;
      break;
    case RobotGaze::Kind::Item:
      view.gaze.kind = agents::GazeKind::Item;
      view.gaze.item = agents::item_index(robot_gaze_.target);
      break;
    case RobotGaze::Kind::Tray: view.gaze.kind = agents::GazeKind::Tray; break;
  }
  // The robot speaks during its step, after the children perceived: its utterance reaches them at the next tick.
  if (robot_speech_started_ >= 0 && robot_speech_started_ > t - kTickS - 1e-9 && robot_speech_started_ < t - 1e-9) {
    agents::SpeechEvent speech;
    speech.kind = agents::Utterance::Comment;
    speech.to = agents::Addressee::Partner;
    speech.duration_s = robot_speaking_until_ - t;
    speech.syllables = static_cast<int>(speech.duration_s * kNaoSyllablesPerS);
    view.speech = speech;
  }
  view.speaking = t < robot_speaking_until_;
}

void SimWorld::step_children(double t) {
  refresh_seen_zones();
  const auto& items = current_items();
  tray_.touches(touches_);
  for (std::size_t i = 0; i < children_.size(); ++i) perceive(children_[i], items, t, perceptions_[i]);
  for (std::size_t i = 0; i < children_.size(); ++i) {
    children_[i].last = child_source_ != nullptr ? child_source_->actions(children_[i].seat_name, t, kTickS)
                                                 : children_[i].agent->step(t, kTickS, perceptions_[i]);
  }
  for (auto& c : children_) apply(c, t);
}

/// What the coder sees of both players this tick (children through their actions, the robot as a child sees it).
void SimWorld::code_players(double t) {
  tray_.touches(touches_);
  const auto observed = [this](const ChildSlot& c) {
    std::array<agents::SeenTouch, 6> touches{};
    int n = 0;
    for (const auto& touch : touches_) {
      if (c.owns_finger(touch.finger) && n < 6) touches[static_cast<std::size_t>(n++)] = {touch.position, agents::item_index(touch.item)};
    }
    return agents::observed_child(c.last, touches, n);
  };
  const agents::ObservedPlayer first = observed(children_[0]);
  agents::ObservedPlayer second;
  if (!child_robot_) {
    second = observed(children_[1]);
  } else {
    const auto& robot = perceptions_[0].partner;
    second.touching = robot.touch_count > 0;
    if (second.touching) {
      second.touch_point = robot.touches[0].point;
      second.touch_item = robot.touches[0].item;
    }
    second.touch_started = second.touching && (!coded_robot_touching_ || second.touch_item != coded_robot_item_);
    coded_robot_touching_ = second.touching;
    coded_robot_item_ = second.touch_item;
    second.gaze = robot.gaze;
    second.speech = robot.speech;
  }
  coder_->observe(t, first, second);
}

void SimWorld::apply(ChildSlot& c, double t) {
  const auto& a = c.last;
  const double at = now();
  if (a.select_colour) {
    tray_.select_colour(*a.select_colour);
    log_.emit({at, "child." + c.seat_name, events::Palette{std::string(sim::palette_name(*a.select_colour))}});
  }
  for (int i = 0; i < a.touch_count; ++i) {
    const auto& cmd = a.touches[static_cast<std::size_t>(i)];
    if (cmd.finger < 1 || cmd.finger > agents::kFingersPerChild) continue;
    const int finger = c.finger_offset + cmd.finger;
    auto& down = c.down[static_cast<std::size_t>(cmd.finger)];
    switch (cmd.phase) {
      case agents::TouchPhase::Down: {
        if (down) tray_.touch_up(finger);
        down = false;
        if (!sim::on_screen(cmd.point)) {
          log_.emit({at, "child." + c.seat_name, events::TouchMissed{cmd.point.x(), cmd.point.y()}});
          break;
        }
        const auto outcome = tray_.touch_down(finger, cmd.point);
        down = true;
        c.last_touch_t = t;
        log_.emit({at, "child." + c.seat_name,
                   events::TouchDown{finger, cmd.point.x(), cmd.point.y(),
                                     outcome == sim::TouchOutcome::GrabbedItem    ? "item"
                                     : outcome == sim::TouchOutcome::StartedStroke ? "stroke"
                                                                                   : "ignored"}});
        break;
      }
      case agents::TouchPhase::Move: {
        if (!down) break;
        const Vec2 p(std::clamp(cmd.point.x(), 0.0, sim::kScreenWidthM),
                     std::clamp(cmd.point.y(), -sim::kScreenHeightM, 0.0));
        tray_.touch_move(finger, p);
        break;
      }
      case agents::TouchPhase::Up:
        if (!down) break;
        tray_.touch_up(finger);
        down = false;
        log_.emit({at, "child." + c.seat_name, events::TouchUp{finger}});
        break;
    }
  }
  if (a.speech) {
    c.speaking_until = t + a.speech->duration_s;
    log_.emit({at, "child." + c.seat_name,
               events::ChildSpeech{std::string(agents::utterance_name(a.speech->kind)),
                                   std::string(agents::addressee_name(a.speech->to)), a.speech->duration_s,
                                   a.speech->syllables}});
  }
  if (a.gaze.kind != c.last_gaze_kind || a.gaze.item != c.last_gaze_item) {
    c.last_gaze_kind = a.gaze.kind;
    c.last_gaze_item = a.gaze.item;
    events::ChildGaze gaze{std::string(agents::gaze_kind_name(a.gaze.kind)), std::nullopt};
    if (a.gaze.kind == agents::GazeKind::Item && a.gaze.item >= 0) {
      gaze.item = std::string(agents::kItemNames[static_cast<std::size_t>(a.gaze.item)]);
    }
    log_.emit({at, "child." + c.seat_name, std::move(gaze)});
  }
  if (a.quit && !c.announced_quit) {
    c.announced_quit = true;
    log_.emit({at, "child." + c.seat_name, events::WantsToStop{}});
  }
}

}  // namespace freeplay::runner::detail
