#include "freeplay/runner/episode.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <span>

#include "freeplay/agents/coder.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/controller_episode.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/results/run_folder.hpp"
#include "sim_world.hpp"

namespace freeplay::runner {

namespace {

using detail::kTickS;
constexpr const char* kRobotHello = "Hello, I'm Nao. Today I'll be playing with you. Exciting!";

/// The protocol of one episode: stages, the 10 Hz free-play loop, observers and the result. The world side
/// (SimWorld) holds the game, the children and the metrics; the robot side (RobotSide) decides for the robot.
class Episode {
 public:
  Episode(const EpisodeInputs& inputs)
      : scenario_(inputs.scenario), seeds_(inputs.seed), world_(inputs.scenario, seeds_, inputs.models) {
    if (!world_.child_robot()) return;
    policies::PolicyContext context;
    context.episode_index = inputs.episode_index;
    for (const auto& item : inputs.models.catalogue->items()) context.item_names.push_back(item.name);
    const auto disc = world_.reach();
    auto executor = make_move_executor(scenario_, disc.centre, disc.radius);
    if (inputs.decisions != nullptr) {  // an action source in front of the robot side: what it asks is reported
      inputs.decisions->reset(context, seeds_.stream("policy"));
      robot_.emplace(*inputs.decisions, std::move(executor), seeds_.stream("planner"), BadMove::Report);
    } else {
      auto policy = policies::make_policy(scenario_.robot.policy, scenario_.robot.params);
      policy->reset(context, seeds_.stream("policy"));
      robot_.emplace(std::move(policy), std::move(executor), seeds_.stream("planner"), BadMove::Throw);
    }
    robot_->set_move_observer(inputs.moves);
    robot_side_acts_ = inputs.robot == nullptr || inputs.decisions != nullptr;
  }

  EpisodeResult run(const EpisodeInputs& inputs, const EpisodeOutputs& outputs) {
    EpisodeResult result;
    const auto& stop = inputs.stop;
    signals_ = inputs.signals;
    world_.set_child_source(inputs.children);
    robot_source_ = inputs.robot;
    observers_ = outputs.observers.empty() ? nullptr : &outputs.observers;
    if (observers_ != nullptr) {
      const auto info = inputs.info();
      for (auto* o : *observers_) o->begin(info);
    }
    const auto wall_start = std::chrono::steady_clock::now();
    auto& tray = world_.tray();
    // Greetings: blank screen; in child-robot sessions the robot stands up and says hello.
    stage_event("greeting");
    if (world_.child_robot()) world_.greet(kRobotHello);
    if (!idle_stage(scenario_.protocol.greeting_s, stop)) return aborted(result);
    // Tutorial: tutorial background, only the boy and the girl (skipped when free play was signalled already).
    if (jump_to_ <= kTutorial) {
      tray.signal(sim::Signal::StartTutorial);
      stage_event("tutorial");
      if (!idle_stage(scenario_.protocol.tutorial_s, stop)) return aborted(result);
    }
    // Free play.
    tray.signal(sim::Signal::StartFreeplay);
    world_.start_freeplay();
    stage_ = "freeplay";
    stage_event("freeplay");
    world_.drain_tray_events();
    const double cap = scenario_.protocol.freeplay_cap_s;
    std::string ended_by = "cap";
    double t = 0.0;
    for (long tick = 0;; ++tick) {
      t = static_cast<double>(tick) * kTickS;
      if (t >= cap) break;
      if (((tick & 63) == 0 || observers_ != nullptr) && stop.load(std::memory_order_relaxed)) return aborted(result);
      poll_signals();
      if (jump_to_ > kFreeplay) {
        ended_by = "signal";
        break;
      }
      world_.step_children(t);
      if (world_.child_robot()) step_robot(t);
      world_.code_players(t);
      tray.step(kTickS);
      world_.drain_tray_events();
      world_.measure_gaze();
      if (observers_ != nullptr) notify();
      if (world_.ended()) {
        t += kTickS;
        ended_by = "quit";
        break;
      }
    }
    const double duration = std::min(t, cap);
    world_.finish_freeplay(duration, ended_by);
    // Debriefing.
    tray.signal(sim::Signal::BlankInterface);
    stage_event("debriefing");
    if (!idle_stage(scenario_.protocol.debriefing_s, stop)) return aborted(result);
    world_.drain_tray_events();

    result.duration_s = duration;
    result.simulated_s = tray.time();
    // The ground truth is what the coder saw; the children's own states stay for the agreement metric.
    const auto& children = world_.children();
    result.annotations.purple = world_.coder().timeline(0);
    if (!world_.child_robot()) result.annotations.yellow = world_.coder().timeline(1);
    result.hit_cap = ended_by == "cap";
    for (const auto& c : children) {
      const auto& coded = c.seat_name == "purple" ? result.annotations.purple : result.annotations.yellow;
      result.children.push_back({c.agent->profile(), coded.value_or(agents::ChildTimeline{}), c.agent->timeline(),
                                 c.agent->quit_time(), c.agent->counters()});
    }
    result.record = world_.record(duration, ended_by, result.annotations);
    result.record["simulated_s"] = result.simulated_s;
    result.record["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    if (observers_ != nullptr) {
      for (auto* o : *observers_) o->end(result);
    }
    result.events = std::move(world_.log());
    return result;
  }

 private:
  // The robot's tick: the finger poses from outside (if any), then the robot side (its policy or the front's
  // decisions, and the one move driver) unless the poses from outside replace it.
  void step_robot(double t) {
    if (robot_source_ != nullptr) world_.apply_external(robot_source_->commands(t, world_.tray(), world_.reach()), t);
    if (robot_side_acts_) robot_->step(t, world_.observe(t, robot_->perceives_children()), world_);
    world_.rest_when_idle(t);
  }

  static constexpr int kTutorial = 1;    // stage indices: greeting 0, tutorial 1, free play 2, debriefing 3
  static constexpr int kFreeplay = 2;
  static constexpr int kDebriefing = 3;

  int stage_index() const {
    if (stage_ == "greeting") return 0;
    if (stage_ == "tutorial") return kTutorial;
    return stage_ == "freeplay" ? kFreeplay : kDebriefing;
  }

  // Applies the signals received since the last tick: a stage signal that starts a later stage ends the current
  // one (and any between); every other signal goes to the game.
  void poll_signals() {
    if (signals_ == nullptr) return;
    for (const auto s : signals_->take()) {
      const int current = stage_index();
      const int target = s == sim::Signal::StartTutorial                              ? kTutorial
                         : s == sim::Signal::StartFreeplay                            ? kFreeplay
                         : s == sim::Signal::BlankInterface && current == kFreeplay ? kDebriefing
                                                                                      : -1;
      world_.log().emit({world_.now(), "protocol", events::SignalReceived{std::string(sim::signal_name(s)), stage_}});
      if (target > current) {
        jump_to_ = std::max(jump_to_, target);
      } else {
        world_.tray().signal(s);
      }
    }
  }

  void stage_event(const std::string& name) {
    stage_ = name;
    world_.log().emit({world_.now(), "protocol", events::Stage{name}});
  }

  EpisodeResult& aborted(EpisodeResult& result) {
    if (observers_ != nullptr) {
      for (auto* o : *observers_) o->abort();
    }
    result.aborted = true;
    return result;
  }

  // A stage without children's play (greetings, tutorial, debriefing): one step without observers or signals;
  // with them, 10 Hz ticks (the sandtray clock is integral, so both give the same state); a signalled later stage
  // ends it early. False when stopped.
  bool idle_stage(double seconds, const std::atomic<bool>& stop) {
    auto& tray = world_.tray();
    if (observers_ == nullptr && signals_ == nullptr) {
      tray.step(seconds);
      world_.drain_tray_events();
      return true;
    }
    const double end = tray.time() + seconds;
    while (tray.time() + kTickS <= end + 1e-9) {
      if (stop.load(std::memory_order_relaxed)) return false;
      poll_signals();
      if (jump_to_ > stage_index()) return true;
      tray.step(kTickS);
      world_.drain_tray_events();
      if (observers_ != nullptr) notify();
    }
    if (end - tray.time() > 1e-9) {
      tray.step(end - tray.time());
      world_.drain_tray_events();
      if (observers_ != nullptr) notify();
    }
    return true;
  }

  // Hands every observer the current tick.
  void notify() {
    EpisodeSnapshot snapshot;
    world_.snapshot(snapshot, stage_);
    const auto& events = world_.log().events();
    snapshot.new_events = std::span<const Event>(events.data() + notified_events_, events.size() - notified_events_);
    notified_events_ = events.size();
    for (auto* o : *observers_) o->observe(snapshot);
  }

  const scenario::Scenario& scenario_;
  SeedSequence seeds_;
  detail::SimWorld world_;
  std::optional<RobotSide> robot_;
  RobotActionSource* robot_source_ = nullptr;  // finger poses from outside, applied first when set
  bool robot_side_acts_ = true;  // the robot side steps (false: the poses from outside replace it)
  const std::vector<EpisodeObserver*>* observers_ = nullptr;  // null: none (idle stages then take one step)
  SignalSource* signals_ = nullptr;  // signals from outside (a live graph), polled every tick
  int jump_to_ = 0;                  // the latest stage a received signal started
  std::string stage_ = "greeting";
  std::size_t notified_events_ = 0;
};

}  // namespace

EpisodeOutputs observed_by(const EpisodeObservers& observers) {
  EpisodeOutputs out;
  for (const auto& o : observers) out.observers.push_back(o.get());
  return out;
}

EpisodeResult run_episode(const EpisodeInputs& inputs, const EpisodeOutputs& outputs) {
  Episode episode(inputs);
  return episode.run(inputs, outputs);
}

EpisodeFunction episode_function(const SharedModels& models, ObserverFactory observers, std::filesystem::path run_dir) {
  return [&models, observers = std::move(observers), run_dir = std::move(run_dir)](const EpisodeTask& task,
                                                                                   const std::atomic<bool>& stop) {
    if (task.variant->scenario.kind == scenario::ScenarioKind::controller) return run_controller_task(task, models, stop);
    const auto id = results::RunFolder::episode_file_id(task.variant->id, task.index);
    EpisodeObservers attached = observers ? observers(task.variant->scenario, run_dir) : EpisodeObservers{};
    auto result = run_episode({.scenario = task.variant->scenario,
                               .seed = task.seed,
                               .models = models,
                               .stop = stop,
                               .id = id,
                               .episode_index = task.index},
                              observed_by(attached));
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
