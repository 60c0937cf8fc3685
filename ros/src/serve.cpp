#include "freeplay/ros/serve.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <deque>
#include <optional>
#include <set>
#include <stdexcept>
#include <string_view>

#include "freeplay/core/rng.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/planning/plan.hpp"
#include "freeplay/recording/camera_topics.hpp"
#include "freeplay/ros/graph.hpp"
#include "freeplay/ros/graph_topics.hpp"
#include "freeplay/ros/localisation_node.hpp"
#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/runner/move_driver.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::ros_live {

namespace {

// What a served episode shares between its publisher (observer) and its external robot.
struct Live {
  ros_graph::SandtrayGraph* graph = nullptr;
  double stamp_origin = 0.0;  // ROS time of sandtray time 0
  double stamp(double t) const { return stamp_origin + t; }
};

class GraphRobot;
void serve_plans(GraphRobot& robot, const sim::Sandtray& tray);

/// Publishes every tick of the episode on the graph (the live episode paces the ticks).
class LivePublisher final : public runner::EpisodeObserver {
 public:
  LivePublisher(Live& live, GraphTopics topics) : live_(live), topics_(std::move(topics)) {}

  void observe(const runner::EpisodeSnapshot& s) override {
    auto& g = *live_.graph;
    g.maintain();
    const double stamp = live_.stamp(s.t);
    g.clock(stamp);
    const bool publish_reach = reach_ && (localisation_ == nullptr || !localisation_->publishes_arm_reach());
    topics_.set_arm_reach(publish_reach ? reach_ : std::nullopt);
    for (const auto& m : topics_.tick(s)) g.publish(m);
    last_t_ = s.t;
    for (const auto& e : s.new_events) publish_event(s.t, e);
    if (robot_ != nullptr) serve_plans(*robot_, *s.tray);
    if (s.stage != "freeplay") {
      for (const auto& p : g.take_poses()) {  // as the game: poses are ignored while the sandbox is hidden
        spdlog::debug("/poses from {} ignored outside free play", p.publisher);
      }
      g.take_look_at();  // the external robot acts in free play only
      g.take_point_at();
    }
    if (localisation_ != nullptr) {  // the simulated NAO's sandtray_localisation node: its own TF message, last
      std::vector<ros_graph::Transform> localised;
      for (const auto& line : localisation_->observe(s, localised)) g.speech(line);
      if (!localised.empty()) g.tf(stamp, localised);
    }
  }

  /// The tick topics it publishes.
  const GraphTopics& topics() const { return topics_; }

  /// Answers `plan_motion` through `robot` at every tick (`--robot external`).
  void set_planner(GraphRobot* robot) { robot_ = robot; }

  /// Runs the marker display and the NAO's localisation node on `robot_localising` (child-robot episodes).
  void set_localisation(ServedLocalisation* localisation) { localisation_ = localisation; }

  /// Notes a signal the graph sent: the stage it starts is not signalled again (the game never echoes a signal).
  void received(const std::string& name) { received_.insert(name); }

  /// Sandtray time of the last tick published.
  double last_t() const { return last_t_; }

  /// Sets the arm-reach disc published as the `arm_reach` frame.
  void set_reach(const runner::ReachDisc& reach) { reach_ = reach; }

 private:
  void publish_event(double t, const Event& e) {
    for (const auto& m : topics_.event(t, e)) {
      // A stage another node signalled is not signalled again (the game never echoes a signal).
      const std::string_view prefix = recording::topics::kSignalsPrefix;
      if (m.topic.starts_with(prefix) && received_.erase(m.topic.substr(prefix.size())) != 0) continue;
      live_.graph->publish(m);
    }
  }

  Live& live_;
  GraphTopics topics_;
  std::optional<runner::ReachDisc> reach_;
  GraphRobot* robot_ = nullptr;
  ServedLocalisation* localisation_ = nullptr;
  double last_t_ = 0.0;
  std::set<std::string> received_;  // stage signals received from the graph, not to be echoed
};

/// The scenario's cameras rendered by the runner's CameraRig, published live under their drivers' topics (colour
/// only; depth stays in recordings).
class LiveCameras final : public runner::FrameSink {
 public:
  LiveCameras(Live& live, int jpeg_quality) : live_(live), jpeg_quality_(jpeg_quality) {}

  void write(const stage::FramePack& frame) override {
    if (frame.rgb.empty()) return;
    const auto topics = recording::camera_topics(frame.camera);
    ros_graph::CameraFrame out;
    out.image_topic = topics.rgb_image;
    out.info_topic = topics.rgb_info;
    out.frame_id = topics.rgb_frame;
    out.format = topics.rgb_format;
    out.jpeg = recording::encode_jpeg(frame.rgb, jpeg_quality_);
    out.width = frame.rgb.cols;
    out.height = frame.rgb.rows;
    out.K = {frame.K.fx, frame.K.fy, frame.K.cx, frame.K.cy};
    live_.graph->camera(live_.stamp(frame.stamp), out);
  }

 private:
  Live& live_;
  int jpeg_quality_;
};

/// `sandtray/signals/*` from other nodes, for the episode to apply (the game's own signals: see sim::Signal); `robot_localising` goes to the
/// NAO's localisation node.
class GraphSignals final : public runner::SignalSource {
 public:
  GraphSignals(ros_graph::SandtrayGraph& graph, LivePublisher& publisher, ServedLocalisation* localisation)
      : graph_(graph), publisher_(publisher), localisation_(localisation) {}

  std::vector<sim::Signal> take() override {
    std::vector<sim::Signal> out;
    for (const auto& name : graph_.take_signals()) {
      if (localisation_ != nullptr && localisation_->on_signal(name, publisher_.last_t())) {
        spdlog::info("received sandtray/signals/{}: the marker field and the NAO's localisation", name);
      } else if (const auto signal = sim::signal_from_name(name)) {
        spdlog::info("received sandtray/signals/{}: applied", name);
        publisher_.received(name);
        out.push_back(*signal);
      } else {
        spdlog::info("received sandtray/signals/{}: not simulated by the game", name);
      }
    }
    return out;
  }

 private:
  ros_graph::SandtrayGraph& graph_;
  LivePublisher& publisher_;
  ServedLocalisation* localisation_;
};

/// `--robot external`: the robot's side on the graph, in front of the episode's one robot side. `/poses` from the
/// graph reach the game as the real game takes them (the Nao follows); `move_sandbox_items` goals, gaze and pointing
/// targets become the robot side's actions (a goal is driven by the episode's one move driver, so the event log holds
/// its move events as an in-process episode's); the driver's poses, feedback and result go back to the graph (as
/// the real core nodes beside the game); `plan_motion` is answered here on the episode's clock.
class GraphRobot final : public runner::RobotActionSource, public policies::PlayPolicy, public runner::MoveObserver {
 public:
  GraphRobot(Live& live, const scenario::Scenario& scenario, LivePublisher& publisher, const SeedSequence& seeds)
      : live_(live), scenario_(scenario), publisher_(publisher), plan_rng_(seeds.stream("serve.plan_motion")) {}

  // ---- the finger poses from the graph (called first at every free-play tick) ----
  runner::RobotCommands commands(double /*t*/, const sim::Sandtray& tray, const runner::ReachDisc& reach) override {
    runner::RobotCommands out;
    publisher_.set_reach(reach);
    for (const auto& p : live_.graph->take_poses()) out.finger.emplace_back(p.x, p.y);
    tray_ = &tray;
    stamp_ = live_.stamp(tray.time());
    return out;
  }

  // ---- the graph's goals and targets as the robot side's actions ----
  std::string name() const override { return "external"; }
  void reset(const policies::PolicyContext& /*context*/, Rng /*rng*/) override {}
  std::vector<policies::Action> decide(const policies::Observation& /*o*/) override {
    auto& g = *live_.graph;
    std::vector<policies::Action> out;
    if (const auto look = g.take_look_at()) {
      out.push_back(policies::LookAt{Eigen::Vector3d((*look)[0], (*look)[1], (*look)[2]), std::nullopt});
    }
    if (const auto point = g.take_point_at()) out.push_back(policies::PointAt{Vec2((*point)[0], (*point)[1])});
    if (auto goal = g.take_goal()) {
      if (const auto why = refusal(*goal, *tray_); !why.empty()) {
        spdlog::warn("move_sandbox_items: aborted goal {}: {}", goal->id, why);
        g.goal_done(goal->id, ros_graph::GoalEnd::Aborted, why);
      } else {
        waiting_.push_back(goal->id);
        out.push_back(policies::MoveItem{goal->item, {goal->x, goal->y}});
      }
    }
    if (running_ && waiting_.empty() && g.cancel_requested(*active_)) out.push_back(policies::CancelMove{});
    return out;
  }

  /// A move the robot side did not drive (its item not on the tray) ends its goal here; the driver's ends came first.
  void on_result(const policies::ActionResult& result) override {
    if (result.kind == policies::ActionResult::Kind::SpeechFinished) return;
    if (ends_heard_ > 0) {
      --ends_heard_;
      return;
    }
    if (waiting_.empty()) return;
    live_.graph->goal_done(waiting_.front(), ros_graph::GoalEnd::Aborted, "not executed: " + result.reason);
    waiting_.pop_front();
  }

  // ---- the driver's moves back to the graph: `/poses`, the action's feedback and result ----
  void move_started(const policies::MoveItem& /*move*/, bool running, double /*t*/) override {
    if (waiting_.empty()) return;  // every move here comes from a graph goal; nothing to report otherwise
    active_ = waiting_.front();
    waiting_.pop_front();
    running_ = running;
  }
  void finger(const planning::TimedPose& pose, double /*t*/) override {
    live_.graph->finger(stamp_, pose.position.x(), pose.position.y());
  }
  void progress(int percentage) override {
    if (active_) live_.graph->goal_feedback(*active_, percentage);
  }
  void move_ended(const policies::MoveItem& /*move*/, const planning::MoveOutcome& outcome, double /*t*/) override {
    const auto end = outcome.status == planning::MoveStatus::Succeeded   ? ros_graph::GoalEnd::Succeeded
                     : outcome.status == planning::MoveStatus::Preempted ? ros_graph::GoalEnd::Preempted
                                                                         : ros_graph::GoalEnd::Aborted;
    const bool by_newer = end == ros_graph::GoalEnd::Preempted && !waiting_.empty();
    const std::string text = by_newer                               ? "preempted by a newer goal"
                             : end == ros_graph::GoalEnd::Succeeded ? ""
                                                                    : outcome.reason() + ": " + outcome.message;
    if (active_) live_.graph->goal_done(*active_, end, text);
    active_.reset();
    running_ = false;
    ++ends_heard_;
  }

  /// Answers the waiting `plan_motion` requests on the game as it is now (map_and_plan serves in every stage).
  void serve_plans(const sim::Sandtray& tray) {
    const auto requests = live_.graph->take_plan_requests();
    if (requests.empty()) return;
    const auto world = runner::sandtray_move_world(tray);
    for (const auto& request : requests) answer(request, tray, world);
  }

 private:
  // A goal the real server would execute blindly is checked first: a clear abort beats a robot dragging nothing.
  std::string refusal(const ros_graph::MoveGoal& goal, const sim::Sandtray& tray) const {
    if (tray.catalogue().find(goal.item) == nullptr) {
      return fmt::format("unknown item '{}' (allowed: {})", goal.item, tray.catalogue().names());
    }
    if (!std::isfinite(goal.x) || !std::isfinite(goal.y) || !std::isfinite(goal.z)) {
      return fmt::format("goal ({}, {}, {}) is not a finite point", goal.x, goal.y, goal.z);
    }
    if (!sim::on_screen({goal.x, goal.y})) {
      return fmt::format("goal ({:.3f}, {:.3f}) is off the screen (sandtray frame: 0 ≤ x ≤ {}, −{} ≤ y ≤ 0)", goal.x,
                         goal.y, sim::kScreenWidthM, sim::kScreenHeightM);
    }
    return "";
  }

  void answer(const ros_graph::PlanRequest& request, const sim::Sandtray& tray, const planning::MoveWorld& world) {
    std::string item = request.frame;
    if (!item.empty() && item.front() == '/') item.erase(0, 1);
    std::vector<std::array<double, 2>> path;
    if (tray.catalogue().find(item) != nullptr && std::isfinite(request.x) && std::isfinite(request.y)) {
      const auto pose = tray.item(item).pose;  // the goal is in the item's frame, the path starts at its origin
      planning::PlanRequest plan;
      plan.item = item;
      plan.start = pose.position();
      plan.goal = pose.position() + Eigen::Rotation2Dd(pose.theta) * Vec2(request.x, request.y);
      plan.obstacles = world.footprints();
      plan.time_budget_s = scenario_.planner.time_budget_s;
      const auto result =
          planning::plan_motion(scenario_.planner.name, plan, plan_rng_, planning::planner_options(scenario_.planner));
      if (!result.ok) spdlog::warn("plan_motion: no path for {}: {}", item, result.message);
      for (const auto& p : result.path) path.push_back({p.position.x(), p.position.y()});
    } else {
      spdlog::warn("plan_motion: no path for frame '{}' to ({}, {}): not an item or not a finite point", request.frame,
                   request.x, request.y);
    }
    live_.graph->answer_plan(request.id, path);
  }

  Live& live_;
  const scenario::Scenario& scenario_;
  LivePublisher& publisher_;
  Rng plan_rng_;                              // the `plan_motion` service's planner stream
  std::deque<std::uint64_t> waiting_;         // goals handed to the robot side, not started yet (in order)
  std::optional<std::uint64_t> active_;       // the goal the driver runs (started, not ended)
  bool running_ = false;                      // the active goal's move streams poses (a cancel can stop it)
  int ends_heard_ = 0;                        // driver ends whose ActionResult has not reached on_result yet
  const sim::Sandtray* tray_ = nullptr;       // the game at the last tick
  double stamp_ = 0.0;                        // ROS time of the last tick
};

void serve_plans(GraphRobot& robot, const sim::Sandtray& tray) { robot.serve_plans(tray); }

}  // namespace

struct GraphSide::Impl {
  Impl(const scenario::Scenario& scenario, std::uint64_t seed, const ServeOptions& options)
      : graph(make_graph(scenario, options)),
        live{graph.get(), ros_graph::wall_now()},
        publisher(live, GraphTopics(seed, static_cast<std::uint64_t>(std::llround(live.stamp_origin * 1e9)),
                                    !options.external_robot, scenario.robot.arm_reach_m)),
        cameras(live, scenario.recording.jpeg_quality) {
    for (const auto& declaration : publisher.topics().declarations()) graph->advertise(declaration);
    const bool child_robot = scenario.condition == scenario::Condition::ChildRobot;
    if (child_robot) {
      const auto body = runner::SharedModels::shipped().robot_body(scenario.robot.mode, scenario.robot.arm_reach_m);
      publisher.set_reach(body->reach());
      localisation::LocaliserSettings settings;
      settings.arm_reach_m = scenario.robot.arm_reach_m;
      localisation = std::make_unique<ServedLocalisation>(settings, runner::renderer_options(scenario.rendering));
      publisher.set_localisation(localisation.get());
    }
    if (options.external_robot && child_robot) {
      robot = std::make_unique<GraphRobot>(live, scenario, publisher, SeedSequence(seed));
      publisher.set_planner(robot.get());
    }
    signals = std::make_unique<GraphSignals>(*graph, publisher, localisation.get());
  }

  static std::unique_ptr<ros_graph::SandtrayGraph> make_graph(const scenario::Scenario& scenario, const ServeOptions& options) {
    std::string error;
    if (!ros_graph::start_ros(options.node_name, options.master_timeout_s, error)) throw std::runtime_error(error);
    const bool child_robot = scenario.condition == scenario::Condition::ChildRobot;
    return std::make_unique<ros_graph::SandtrayGraph>(
        ros_graph::NodeOptions{options.node_name, options.rate != 1.0, options.external_robot && child_robot});
  }

  std::unique_ptr<ros_graph::SandtrayGraph> graph;
  Live live;
  LivePublisher publisher;
  LiveCameras cameras;
  std::unique_ptr<ServedLocalisation> localisation;
  std::unique_ptr<GraphRobot> robot;
  std::unique_ptr<GraphSignals> signals;
};

GraphSide::GraphSide(const scenario::Scenario& scenario, std::uint64_t seed, const ServeOptions& options)
    : impl_(std::make_unique<Impl>(scenario, seed, options)) {}

GraphSide::~GraphSide() = default;

runner::EpisodeObserver& GraphSide::publisher() { return impl_->publisher; }

runner::FrameSink& GraphSide::cameras() { return impl_->cameras; }

runner::SignalSource& GraphSide::signals() { return *impl_->signals; }

runner::EpisodeInputs GraphSide::inputs(const scenario::Scenario& scenario, std::uint64_t seed) {
  auto* robot = impl_->robot.get();
  return {.scenario = scenario,
          .seed = seed,
          .id = "serve",
          .decisions = robot,
          .robot = robot,
          .moves = robot,
          .signals = impl_->signals.get()};
}

runner::EpisodeResult serve(const scenario::Scenario& scenario, std::uint64_t seed, const ServeOptions& options,
                            const std::atomic<bool>& stop, runner::PacingTiming* timing) {
  GraphSide side(scenario, seed, options);
  runner::LiveEpisode live(options.rate, stop);
  live.attach(side.publisher());
  std::unique_ptr<runner::CameraRig> rig;
  if (!scenario.cameras.empty()) {  // rendered after the tick's topics went out, at each camera's own rate
    rig = std::make_unique<runner::CameraRig>(scenario, runner::renderer_options(scenario.rendering),
                                              std::vector<runner::FrameSink*>{&side.cameras()});
    live.attach(*rig);
  }
  auto result = live.run(side.inputs(scenario, seed));
  if (timing != nullptr) *timing = live.timing();
  return result;
}

}  // namespace freeplay::ros_live
