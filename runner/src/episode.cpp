#include "freeplay/runner/episode.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <span>

#include "freeplay/agents/child_agent.hpp"
#include "freeplay/agents/coder.hpp"
#include "freeplay/agents/labels.hpp"
#include "freeplay/agents/perception.hpp"
#include "freeplay/agents/profile.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/statistics.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/planning/plan.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/controller_episode.hpp"
#include "freeplay/runner/episode_metrics.hpp"
#include "freeplay/runner/perception_model.hpp"
#include "freeplay/runner/run_folder.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/runner/versions.hpp"
#include "freeplay/sim/canvas.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::runner {

namespace {

constexpr double kTickS = 0.1;                  // the game's 10 Hz tick
constexpr double kRobotArticulationSyllablesPerS = 3.5;  // NAO text-to-speech at its default speed
constexpr double kRobotRestAfterS = 30.0;       // nao_behaviours: arm to rest after 30 s without poses
// Approximate faces for gaze targets (sandtray frame, m): seated children on the long sides, the Nao's head
// above the yellow side, the experimenter standing behind the purple side.
const Eigen::Vector3d kPurpleFace{0.30, -0.60, 0.25};
const Eigen::Vector3d kYellowFace{0.30, 0.265, 0.25};
const Eigen::Vector3d kRobotHead{0.30, 0.20, 0.35};
const Eigen::Vector3d kExperimenter{-0.60, -0.90, 1.20};
constexpr const char* kRobotHello = "Hello, I'm Nao. Today I'll be playing with you. Exciting!";

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

agents::ChildProfile make_profile(const ChildSpec& spec, const agents::Population& population,
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

nlohmann::json profile_json(const agents::ChildProfile& p) {
  static const char* tablet[] = {"0", "1", "2", "na"};
  return {{"age", p.age_years},
          {"gender", std::string(agents::gender_name(p.gender))},
          {"sociability", p.sociability},
          {"assertiveness", p.assertiveness},
          {"attention_span", p.attention_span},
          {"tablet_familiarity", tablet[static_cast<int>(p.tablet)]}};
}

/// One seated child: its agent, finger bookkeeping and per-episode counters.
struct ChildSlot {
  std::string seat_name;
  agents::Seat seat = agents::Seat::Bottom;
  int finger_offset = 0;  // local fingers 1…3 → touch(offset+1 … offset+3)
  std::unique_ptr<agents::ChildAgent> agent;
  agents::ChildActions last;
  std::array<bool, agents::kFingersPerChild + 1> down{};
  double speaking_until = -1.0;
  double last_touch_t = -1e9;
  bool announced_quit = false;
  agents::GazeKind last_gaze_kind = agents::GazeKind::Away;
  int last_gaze_item = -1;

  bool owns_finger(int finger) const { return finger > finger_offset && finger <= finger_offset + agents::kFingersPerChild; }
  bool speaking(double t) const { return t < speaking_until; }
};

/// What the robot is looking at, as the children see it.
struct RobotGaze {
  enum class Kind { Tray, Item, Child } kind = Kind::Tray;
  std::string target;  // item name or seat
};

/// The robot body as the executor's arm follower (`nao_behaviours` following `/poses`).
class BodyFollower final : public planning::ArmFollower {
 public:
  explicit BodyFollower(RobotBody& body) : body_(body) {}
  planning::FollowReport follow(const Vec2& finger, double /*t*/) override {
    const auto reach = body_.reach();
    return {body_.follow_finger(finger), (finger - reach.centre).norm() < reach.radius};
  }

 private:
  RobotBody& body_;
};

class Episode {
 public:
  Episode(const Scenario& scenario, std::uint64_t seed, const SharedModels& models)
      : scenario_(scenario), models_(models), seeds_(seed),
        tray_(models.catalogue, tray_config(), seeds_.stream("sandtray")),
        child_robot_(scenario.condition == "child-robot") {
    const auto& params = *models.child_params;
    const auto population = population_of(scenario);
    add_child("purple", agents::Seat::Bottom, 0, make_profile(scenario.children.purple, population, params,
                                                              seeds_.stream("profile.purple")));
    if (!child_robot_) {
      add_child("yellow", agents::Seat::Top, agents::kFingersPerChild,
                make_profile(scenario.children.yellow, population, params, seeds_.stream("profile.yellow")));
    } else {
      policy_ = policies::make_policy(scenario.robot.policy, scenario.robot.params);
      policies::PolicyContext context;
      for (const auto& item : models.catalogue->items()) context.item_names.push_back(item.name);
      policy_->reset(context, seeds_.stream("policy"));
      body_ = models.robot_body(scenario.robot.mode, scenario.robot.arm_reach_m);
      follower_ = std::make_unique<BodyFollower>(*body_);
      const auto disc = body_->reach();
      executor_ = make_move_executor(scenario, disc.centre, disc.radius);
      planner_rng_ = seeds_.stream("planner");
      perception_ = std::make_unique<PerceptionModel>(
          scenario.perception,
          seeds_.stream("perception"));
    }
  }

  EpisodeResult run(const std::atomic<bool>& stop, EpisodeObservers* observers = nullptr,
                    const EpisodeInfo* info = nullptr, ChildActionSource* child_source = nullptr,
                    RobotActionSource* robot_source = nullptr) {
    EpisodeResult result;
    child_source_ = child_source;
    robot_source_ = robot_source;
    observers_ = observers != nullptr && !observers->empty() ? observers : nullptr;
    if (observers_ != nullptr) {
      for (auto& o : *observers_) o->begin(*info);
    }
    const auto wall_start = std::chrono::steady_clock::now();
    // Greetings: blank screen; in child-robot sessions the robot stands up and says hello.
    stage_event("greeting");
    if (child_robot_) robot_say(kRobotHello, "", 0.0, /*count_as_action=*/false);
    if (!idle_stage(scenario_.protocol.greeting_s, stop)) return aborted(result);
    // Tutorial: tutorial background, only the boy and the girl.
    tray_.signal(sim::Signal::StartTutorial);
    stage_event("tutorial");
    if (!idle_stage(scenario_.protocol.tutorial_s, stop)) return aborted(result);
    // Free play.
    tray_.signal(sim::Signal::StartFreeplay);
    freeplay_start_ = tray_.time();
    freeplay_map_ = tray_.background().clone();
    stage_ = "freeplay";
    stage_event("freeplay");
    coder_.emplace(models_.child_params->coder, child_robot_);
    drain_tray_events();
    const double cap = scenario_.protocol.freeplay_cap_s;
    std::string ended_by = "cap";
    double t = 0.0;
    for (long tick = 0;; ++tick) {
      t = static_cast<double>(tick) * kTickS;
      if (t >= cap) break;
      if (((tick & 63) == 0 || observers_ != nullptr) && stop.load(std::memory_order_relaxed)) return aborted(result);
      step_children(t);
      if (child_robot_) {
        if (robot_source_ != nullptr) step_external_robot(t); else step_robot(t);
      }
      code_players(t);
      tray_.step(kTickS);
      drain_tray_events();
      metrics_.measure_gaze();
      if (observers_ != nullptr) notify();
      if (ended()) {
        t += kTickS;
        ended_by = "quit";
        break;
      }
    }
    const double duration = std::min(t, cap);
    drawing_coverage_ = sim::differing_pixel_share(tray_.background(), freeplay_map_);
    log_.emit({freeplay_start_ + duration, "protocol", "freeplay_ended", {{"ended_by", ended_by}, {"duration_s", duration}}});
    for (auto& c : children_) c.agent->finish(duration);
    coder_->finish(duration);
    // Debriefing.
    tray_.signal(sim::Signal::BlankInterface);
    stage_event("debriefing");
    if (!idle_stage(scenario_.protocol.debriefing_s, stop)) return aborted(result);
    drain_tray_events();

    result.duration_s = duration;
    result.simulated_s = tray_.time();
    // The ground truth is what the coder saw; the children's own states stay for the agreement metric.
    result.annotations.purple = agents::with_coded_social(children_[0].agent->timeline(), coder_->timeline(0));
    if (!child_robot_) {
      result.annotations.yellow = agents::with_coded_social(children_[1].agent->timeline(), coder_->timeline(1));
    }
    result.hit_cap = ended_by == "cap";
    for (const auto& c : children_) {
      const auto& coded = c.seat_name == "purple" ? result.annotations.purple : result.annotations.yellow;
      result.children.push_back({c.agent->profile(), coded.value_or(agents::ChildTimeline{}), c.agent->timeline(),
                                 c.agent->quit_time(), c.agent->counters()});
    }
    result.record = record(duration, ended_by, result.annotations);
    result.record["simulated_s"] = result.simulated_s;
    result.record["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    if (observers_ != nullptr) {
      for (auto& o : *observers_) o->end(result);
    }
    result.events = std::move(log_);
    return result;
  }

 private:
  static agents::Population population_of(const Scenario& s) {
    if (s.children.population == "pinsoro-cc") return agents::Population::pinsoro_child_child();
    if (s.children.population == "pinsoro-cr") return agents::Population::pinsoro_child_robot();
    return s.condition == "child-robot" ? agents::Population::pinsoro_child_robot()
                                        : agents::Population::pinsoro_child_child();
  }

  static sim::SandtrayConfig tray_config() {
    sim::SandtrayConfig config;
    config.raster_width_px = 960;  // zones are segmented at 200 px anyway; half the raster cost
    return config;
  }

  void add_child(const std::string& seat_name, agents::Seat seat, int finger_offset, agents::ChildProfile profile) {
    ChildSlot c;
    c.seat_name = seat_name;
    c.seat = seat;
    c.finger_offset = finger_offset;
    c.agent = std::make_unique<agents::ChildAgent>(*models_.child_params, profile, seat,
                                                   seeds_.stream("child." + seat_name));
    children_.push_back(std::move(c));
  }

  void stage_event(const std::string& name) {
    stage_ = name;
    log_.emit({tray_.time(), "protocol", "stage", {{"stage", name}}});
  }

  EpisodeResult& aborted(EpisodeResult& result) {
    if (observers_ != nullptr) {
      for (auto& o : *observers_) o->abort();
    }
    result.aborted = true;
    return result;
  }

  // A stage without children's play (greetings, tutorial, debriefing): one step without observers; with them,
  // 10 Hz ticks (the sandtray clock is integral, so both give the same state). False when stopped.
  bool idle_stage(double seconds, const std::atomic<bool>& stop) {
    if (observers_ == nullptr) {
      tray_.step(seconds);
      drain_tray_events();
      return true;
    }
    const double end = tray_.time() + seconds;
    while (tray_.time() + kTickS <= end + 1e-9) {
      if (stop.load(std::memory_order_relaxed)) return false;
      tray_.step(kTickS);
      drain_tray_events();
      notify();
    }
    if (end - tray_.time() > 1e-9) {
      tray_.step(end - tray_.time());
      drain_tray_events();
      notify();
    }
    return true;
  }

  Eigen::Vector3d face_of(const std::string& seat) const {
    if (child_robot_ && seat == "purple") return body_->child_face(seat);
    return seat == "yellow" ? kYellowFace : kPurpleFace;
  }

  Eigen::Vector3d gaze_point_of(const ChildSlot& c) const {
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

  // Hands every observer the current tick.
  void notify() {
    const double t_abs = tray_.time();
    const bool started = stage_ == "freeplay" || stage_ == "debriefing";
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
      s.speaking = stage_ == "freeplay" && c.speaking(freeplay_t);
    }
    EpisodeSnapshot snapshot;
    snapshot.t = t_abs;
    snapshot.freeplay_t = freeplay_t;
    snapshot.stage = stage_;
    snapshot.tray = &tray_;
    snapshot.children = snapshot_children_;
    if (child_robot_) {
      robot_snapshot_.joint_names.clear();
      robot_snapshot_.positions.clear();
      robot_snapshot_.velocities.clear();
      robot_snapshot_.efforts.clear();
      body_->joint_state(robot_snapshot_);
      robot_snapshot_.finger = executor_->status() == planning::MoveStatus::Running ? robot_finger_ : std::nullopt;
      robot_snapshot_.gaze_point = robot_gaze_point_;
      robot_snapshot_.speaking = t_abs < robot_speaking_until_abs_;
      snapshot.robot = &robot_snapshot_;
    }
    const auto& events = log_.events();
    snapshot.new_events = std::span<const Event>(events.data() + notified_events_, events.size() - notified_events_);
    notified_events_ = events.size();
    for (auto& o : *observers_) o->observe(snapshot);
  }

  double now() const { return tray_.time(); }

  bool ended() const {
    if (child_source_ != nullptr) {
      return std::all_of(children_.begin(), children_.end(), [](const ChildSlot& c) { return c.announced_quit; });
    }
    if (child_robot_) return children_[0].agent->wants_to_stop();
    return children_[0].agent->wants_to_stop() && children_[1].agent->wants_to_stop();
  }

  // ---- children --------------------------------------------------------------------------------------------

  void refresh_seen_zones() {
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

  void perceive(const ChildSlot& me, const std::vector<sim::ItemState>& items, double t,
                agents::ChildPerception& seen) const {
    seen.item_count = 0;
    for (const auto& item : items) {
      if (!item.visible || seen.item_count >= static_cast<int>(agents::kMaxSeenItems)) continue;
      const int index = agents::item_index(item.name);
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
      for (const auto& touch : tray_.touches()) {
        if (!other.owns_finger(touch.finger) || view.touch_count >= 6) continue;
        view.touches[static_cast<std::size_t>(view.touch_count++)] = {touch.position, agents::item_index(touch.item)};
      }
      view.gaze = other.last.gaze;
      view.speech = other.last.speech;
      view.speaking = other.speaking(t);
      view.wants_to_stop = other.agent->wants_to_stop();
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
      speech.syllables = static_cast<int>(speech.duration_s * kRobotArticulationSyllablesPerS);
      view.speech = speech;
    }
    view.speaking = t < robot_speaking_until_;
  }

  void step_children(double t) {
    refresh_seen_zones();
    const auto items = tray_.items();
    for (std::size_t i = 0; i < children_.size(); ++i) perceive(children_[i], items, t, perceptions_[i]);
    for (std::size_t i = 0; i < children_.size(); ++i) {
      children_[i].last = child_source_ != nullptr ? child_source_->actions(children_[i].seat_name, t, kTickS)
                                                   : children_[i].agent->step(t, kTickS, perceptions_[i]);
    }
    for (auto& c : children_) apply(c, t);
  }

  /// What the coder sees of both players this tick (children through their actions, the robot as a child sees it).
  void code_players(double t) {
    const auto observed = [this](const ChildSlot& c) {
      std::array<agents::SeenTouch, 6> touches{};
      int n = 0;
      for (const auto& touch : tray_.touches()) {
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

  void apply(ChildSlot& c, double t) {
    const auto& a = c.last;
    const double at = now();
    if (a.select_colour) {
      tray_.select_colour(*a.select_colour);
      log_.emit({at, "child." + c.seat_name, "palette", {{"colour", std::string(sim::palette_name(*a.select_colour))}}});
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
            log_.emit({at, "child." + c.seat_name, "touch_missed", {{"x", cmd.point.x()}, {"y", cmd.point.y()}}});
            break;
          }
          const auto outcome = tray_.touch_down(finger, cmd.point);
          down = true;
          c.last_touch_t = t;
          log_.emit({at, "child." + c.seat_name, "touch_down",
                     {{"finger", finger},
                      {"x", cmd.point.x()},
                      {"y", cmd.point.y()},
                      {"outcome", outcome == sim::TouchOutcome::GrabbedItem    ? "item"
                                  : outcome == sim::TouchOutcome::StartedStroke ? "stroke"
                                                                                : "ignored"}}});
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
          log_.emit({at, "child." + c.seat_name, "touch_up", {{"finger", finger}}});
          break;
      }
    }
    if (a.speech) {
      c.speaking_until = t + a.speech->duration_s;
      log_.emit({at, "child." + c.seat_name, "speech",
                 {{"kind", std::string(agents::utterance_name(a.speech->kind))},
                  {"to", std::string(agents::addressee_name(a.speech->to))},
                  {"duration_s", a.speech->duration_s},
                  {"syllables", a.speech->syllables}}});
    }
    if (a.gaze.kind != c.last_gaze_kind || a.gaze.item != c.last_gaze_item) {
      c.last_gaze_kind = a.gaze.kind;
      c.last_gaze_item = a.gaze.item;
      nlohmann::json data{{"target", std::string(agents::gaze_kind_name(a.gaze.kind))}};
      if (a.gaze.kind == agents::GazeKind::Item && a.gaze.item >= 0) {
        data["item"] = std::string(agents::kItemNames[static_cast<std::size_t>(a.gaze.item)]);
      }
      log_.emit({at, "child." + c.seat_name, "gaze", std::move(data)});
    }
    if (a.quit && !c.announced_quit) {
      c.announced_quit = true;
      log_.emit({at, "child." + c.seat_name, "wants_to_stop", nullptr});
    }
  }

  // ---- robot -----------------------------------------------------------------------------------------------

  // The robot's observation, reusing last tick's buffers; the zones are copied only after a new background.
  const policies::Observation& observe(double t) {
    policies::Observation& o = observation_;
    o.t = t;
    o.items.clear();
    for (const auto& item : tray_.items()) {
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
    for (const auto& touch : tray_.touches()) o.touches.push_back({touch.finger, touch.position});
    o.children.clear();
    o.self = {};
    o.interaction_events = std::move(pending_interaction_events_);
    pending_interaction_events_.clear();
    if (policy_->perceives_children()) {
      const auto& c = children_[0];
      ChildTruth truth;
      truth.seat = c.seat_name;
      truth.gaze = c.last.gaze.kind;
      truth.gaze_point = c.last.gaze.point;
      truth.speaking = c.speaking(t);
      truth.speech_to_partner = c.last.speech && c.last.speech->to == agents::Addressee::Partner;
      truth.seconds_since_touch = t - c.last_touch_t;
      for (const auto& touch : tray_.touches()) {
        if (c.owns_finger(touch.finger) && !touch.item.empty()) truth.moving_item = touch.item;
      }
      o.children.push_back(perception_->perceive(truth, t));
    }
    const auto reach = body_->reach();
    o.self.arm_reach_known = true;
    o.self.arm_reach_centre = reach.centre;
    o.self.arm_reach_radius = reach.radius;
    o.self.moving_item = executor_->status() == planning::MoveStatus::Running;
    o.self.current_item = current_move_item_;
    o.self.speaking = t < robot_speaking_until_;
    return o;
  }

  void robot_say(const std::string& text, const std::string& to, double t, bool count_as_action) {
    const double duration = syllables_of(text) / kRobotArticulationSyllablesPerS;
    robot_speech_started_ = t;
    robot_speaking_until_ = t + duration;
    robot_speaking_until_abs_ = now() + duration;
    speech_pending_result_ = count_as_action;
    log_.emit({now(), "robot", "say", {{"text", text}, {"to", to}, {"duration_s", duration}}});
  }

  void start_move(const policies::MoveItem& move, double t) {
    if (!std::isfinite(move.target.x()) || !std::isfinite(move.target.y()) ||
        models_.catalogue->find(move.item) == nullptr) {
      throw InputError(fmt::format("policy '{}' at free-play t = {:.1f} s asked to move '{}' to ({}, {})",
                                   policy_->name(), t, move.item, move.target.x(), move.target.y()),
                       "MoveItem", fmt::format("an item of {} and a finite target", models_.catalogue->names()));
    }
    executor_->start({move.item, move.target}, move_world(), planner_rng_);
    move_unreported_ = executor_->status() != planning::MoveStatus::Running;
    current_move_item_ = move.item;
    move_target_ = move.target;
    log_.emit({now(), "robot", "move_goal", {{"item", move.item}, {"x", move.target.x()}, {"y", move.target.y()}}});
    robot_gaze_ = {RobotGaze::Kind::Item, move.item};
  }

  planning::MoveWorld move_world() const { return sandtray_move_world(tray_); }

  void handle(const policies::Action& action, double t) {
    if (const auto* move = std::get_if<policies::MoveItem>(&action)) {
      start_move(*move, t);
    } else if (const auto* look = std::get_if<policies::LookAt>(&action)) {
      if (look->child) {
        robot_gaze_ = {RobotGaze::Kind::Child, *look->child};
        robot_gaze_point_ = body_->child_face(*look->child);
        body_->look_at(robot_gaze_point_);
        log_.emit({now(), "robot", "look_at", {{"child", *look->child}}});
      } else if (look->point) {
        robot_gaze_ = {RobotGaze::Kind::Tray, ""};
        for (const auto& item : tray_.items()) {
          if ((item.pose.position() - look->point->head<2>()).norm() < 0.03) robot_gaze_ = {RobotGaze::Kind::Item, item.name};
        }
        body_->look_at(*look->point);
        robot_gaze_point_ = *look->point;
        nlohmann::json data{{"x", look->point->x()}, {"y", look->point->y()}, {"z", look->point->z()}};
        if (robot_gaze_.kind == RobotGaze::Kind::Item) data["item"] = robot_gaze_.target;  // the item looked at
        log_.emit({now(), "robot", "look_at", std::move(data)});
      }
    } else if (const auto* point = std::get_if<policies::PointAt>(&action)) {
      body_->point_at(point->point);
      last_pose_t_ = t;
      log_.emit({now(), "robot", "point_at", {{"x", point->point.x()}, {"y", point->point.y()}}});
    } else if (const auto* say = std::get_if<policies::Say>(&action)) {
      robot_say(say->text, say->addressee, t, true);
    } else if (std::holds_alternative<policies::CancelMove>(action)) {
      executor_->cancel();
      log_.emit({now(), "robot", "cancel", nullptr});
    }
  }

  void step_robot(double t) {
    for (const auto& action : policy_->decide(observe(t))) handle(action, t);
    if (move_unreported_) {  // a move that ended in start() (refused or unplannable)
      move_unreported_ = false;
      finish_move(executor_->status());
    }
    if (executor_->status() == planning::MoveStatus::Running) {
      planning::MoveOutputs outputs;
      outputs.finger = [&](const planning::TimedPose& pose) {
        tray_.robot_pose(pose.position);
        robot_finger_ = pose.position;
        robot_gaze_point_ = {pose.position.x(), pose.position.y(), 0.0};
        last_pose_t_ = t;
      };
      outputs.arm = follower_.get();
      executor_->step(kTickS, move_world(), outputs);
      if (executor_->status() != planning::MoveStatus::Running) finish_move(executor_->status());
    }
    if (speech_pending_result_ && t >= robot_speaking_until_) {
      speech_pending_result_ = false;
      policy_->on_result({policies::ActionResult::Kind::SpeechFinished, "", ""});
    }
    rest_when_idle(t);
  }

  // ---- external robot (RobotActionSource): finger poses reach the game as `/poses` do; gaze, pointing the Nao ---

  void step_external_robot(double t) {
    const auto commands = robot_source_->commands(t, tray_, body_->reach());
    for (const auto& p : commands.finger) {
      tray_.robot_pose(p);
      robot_finger_ = p;
      robot_gaze_point_ = {p.x(), p.y(), 0.0};
      body_->follow_finger(p);
      last_pose_t_ = t;
    }
    if (commands.look_at) {
      body_->look_at(*commands.look_at);
      robot_gaze_point_ = *commands.look_at;
      log_.emit({now(), "robot", "look_at", {{"x", commands.look_at->x()}, {"y", commands.look_at->y()},
                                             {"z", commands.look_at->z()}}});
    }
    if (commands.point_at) {
      body_->point_at(*commands.point_at);
      last_pose_t_ = t;
      log_.emit({now(), "robot", "point_at", {{"x", commands.point_at->x()}, {"y", commands.point_at->y()}}});
    }
    rest_when_idle(t);
  }

  // nao_behaviours: the arm goes to rest after 30 s without poses.
  void rest_when_idle(double t) {
    if (last_pose_t_ > -1e8 && t - last_pose_t_ > kRobotRestAfterS) {
      body_->rest();
      last_pose_t_ = -1e9;
    }
  }

  void finish_move(planning::MoveStatus status) {
    const auto& outcome = executor_->current();
    policies::ActionResult result;
    result.item = current_move_item_;
    nlohmann::json data{{"item", current_move_item_},
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
        pending_placement_[current_move_item_] = move_target_;
        break;
      case planning::MoveStatus::Preempted:
        result.kind = policies::ActionResult::Kind::MoveCancelled;
        break;
      default:
        result.kind = policies::ActionResult::Kind::MoveFailed;
        result.reason = outcome.reason();
        break;
    }
    log_.emit({now(), "robot", "move_result", std::move(data)});
    robot_gaze_ = {RobotGaze::Kind::Tray, ""};
    policy_->on_result(result);
  }

  // ---- events and metrics ----------------------------------------------------------------------------------

  void drain_tray_events() {
    for (auto& e : tray_.drain_events()) {
      if (e.type == "interaction_event") {
        const auto message = e.data.value("message", "");
        pending_interaction_events_.push_back(message);
        if (message.rfind("releasing_", 0) == 0) on_robot_release(message.substr(10));
      }
      log_.emit(std::move(e));
    }
    metrics_.observe_new(log_, tray_.time(), SandtrayMetricsWorld(tray_));
  }

  void on_robot_release(const std::string& item) {
    const auto it = pending_placement_.find(item);
    if (it == pending_placement_.end() || models_.catalogue->find(item) == nullptr) return;
    const Vec2 at = tray_.item(item).pose.position();
    if (executor_->status() != planning::MoveStatus::Running) executor_->observe_release(at);
    pending_placement_.erase(it);
  }

  nlohmann::json record(double duration, const std::string& ended_by, const agents::SessionAnnotations& annotations) {
    const auto metrics = metrics_.to_json(duration, annotations, drawing_coverage_);
    nlohmann::json children = nlohmann::json::object();
    for (const auto& c : children_) {
      children[c.seat_name] = profile_json(c.agent->profile());
      children[c.seat_name]["quit_time_s"] = c.agent->quit_time();
      // How often the coded social label equals the child's own state (the child's state is not in a bag).
      const auto& coded = c.seat_name == "purple" ? annotations.purple : annotations.yellow;
      if (coded) {
        children[c.seat_name]["coder_agreement"] =
            agents::timeline_agreement(*coded, c.agent->timeline(), agents::Axis::SocialEngagement, duration);
      }
    }
    auto out = provenance_fields(log_);
    out.update({{"duration_s", duration},
                {"ended_by", ended_by},
                {"children", children},
                {"robot_mode", child_robot_ ? scenario_.robot.mode : ""},
                {"planner", child_robot_ ? scenario_.planner.name : ""},
                {"metrics", metrics}});
    return out;
  }

  const Scenario& scenario_;
  const SharedModels& models_;
  SeedSequence seeds_;
  sim::Sandtray tray_;
  bool child_robot_;
  EventLog log_;
  double freeplay_start_ = 0.0;
  std::vector<ChildSlot> children_;
  std::optional<agents::PairCoder> coder_;
  bool coded_robot_touching_ = false;
  int coded_robot_item_ = -1;
  std::array<agents::ChildPerception, 2> perceptions_{};
  std::array<agents::SeenZone, agents::kMaxSeenZones> seen_zones_{};
  int seen_zone_count_ = 0;
  std::uint64_t seen_zones_version_ = ~std::uint64_t{0};
  std::vector<policies::ZoneObservation> observation_zones_;
  policies::Observation observation_;                      // the robot's observation, reused every tick
  std::uint64_t observed_zones_version_ = ~std::uint64_t{0};  // seen_zones_version_ of observation_.zones
  // Robot.
  std::unique_ptr<policies::PlayPolicy> policy_;
  std::unique_ptr<planning::MoveExecutor> executor_;
  Rng planner_rng_{0};
  std::unique_ptr<RobotBody> body_;
  std::unique_ptr<BodyFollower> follower_;
  std::unique_ptr<PerceptionModel> perception_;
  RobotGaze robot_gaze_;
  std::string current_move_item_;
  Vec2 move_target_ = Vec2::Zero();
  double robot_speech_started_ = -1.0;
  double robot_speaking_until_ = -1.0;
  bool speech_pending_result_ = false;
  double last_pose_t_ = -1e9;
  std::vector<std::string> pending_interaction_events_;
  std::map<std::string, Vec2> pending_placement_;
  // Metrics.
  EpisodeMetrics metrics_{child_robot_};  // fed the event log at every drain of the tray's events
  cv::Mat freeplay_map_;          // the background published when free play started (the bare map)
  double drawing_coverage_ = 0.0;  // share of the map drawn over in the last background published in free play
  bool move_unreported_ = false;
  ChildActionSource* child_source_ = nullptr;  // replaces the agents' actions when set
  RobotActionSource* robot_source_ = nullptr;  // replaces the robot's policy and executor when set
  // Observers.
  EpisodeObservers* observers_ = nullptr;
  std::string stage_ = "greeting";
  std::size_t notified_events_ = 0;
  std::vector<ChildSnapshot> snapshot_children_;
  RobotSnapshot robot_snapshot_;
  std::optional<Vec2> robot_finger_;
  Eigen::Vector3d robot_gaze_point_{sim::kScreenWidthM / 2, -sim::kScreenHeightM / 2, 0.0};
  double robot_speaking_until_abs_ = -1.0;
};

}  // namespace

EpisodeResult run_episode(const Scenario& scenario, std::uint64_t seed, const SharedModels& models,
                          const std::atomic<bool>& stop) {
  Episode episode(scenario, seed, models);
  return episode.run(stop);
}

EpisodeResult run_episode(const Scenario& scenario, std::uint64_t seed, const SharedModels& models,
                          const std::atomic<bool>& stop, EpisodeObservers& observers, const EpisodeInfo& info,
                          ChildActionSource* children, RobotActionSource* robot) {
  Episode episode(scenario, seed, models);
  return episode.run(stop, &observers, &info, children, robot);
}

EpisodeFunction episode_function(const SharedModels& models, ObserverFactory observers, std::filesystem::path run_dir) {
  return [&models, observers = std::move(observers), run_dir = std::move(run_dir)](const EpisodeTask& task,
                                                                                   const std::atomic<bool>& stop) {
    if (task.variant->scenario.kind == "controller") return run_controller_task(task, models, stop);
    const auto id = RunFolder::episode_file_id(task.variant->id, task.index);
    EpisodeObservers attached = observers ? observers(task.variant->scenario, run_dir) : EpisodeObservers{};
    const EpisodeInfo info{&task.variant->scenario, id, task.seed};
    auto result = attached.empty() ? run_episode(task.variant->scenario, task.seed, models, stop)
                                   : run_episode(task.variant->scenario, task.seed, models, stop, attached, info);
    EpisodeOutput out;
    if (result.aborted) return out;
    out.record = std::move(result.record);
    out.simulated_s = result.simulated_s;
    if (task.events) out.files["events/" + id + ".jsonl"] = result.events.to_jsonl();
    out.files["annotations/" + id + ".yaml"] = agents::to_pinsoro_yaml(
        result.annotations, 0.0,
        fmt::format("Synthetic ground truth by freeplay-sim: {} episode {} seed {} (times: s since free play started)",
                    task.variant->id, task.index, task.seed));
    return out;
  };
}

}  // namespace freeplay::runner
