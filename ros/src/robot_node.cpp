#include "freeplay/ros/robot_node.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <thread>

#include "freeplay/core/error.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/planning/plan.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/ros/graph.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/ros/graph_messages.hpp"

namespace freeplay::ros_live {

namespace {

constexpr double kTickS = 0.1;             // decision and /poses rate (10 Hz)
constexpr double kTouchFreshS = 0.35;      // a touchN frame older than this is a lifted finger (the game sends 10 Hz)
constexpr double kSpeechSPerChar = 0.075;  // speaking time per character before SpeechFinished (no TTS feedback)

/// The sandtray as the graph shows it at one tick.
struct GraphWorld {
  std::map<std::string, Pose2> items;              // TF frames of catalogue items
  std::map<std::string, Polygon2> footprints;      // /footprints, in each item's own frame
  std::vector<std::pair<int, Vec2>> fingers;       // fresh touchN frames: (N, position)
  std::optional<std::array<double, 3>> arm_reach;  // x, y, radius

  bool touched(const std::string& item) const {
    const auto pose = items.find(item);
    const auto shape = footprints.find(item);
    if (pose == items.end() || shape == footprints.end()) return false;
    const auto polygon = transformed(shape->second, pose->second);
    for (const auto& [n, p] : fingers) {
      if (point_in_polygon(polygon, p)) return true;
    }
    return false;
  }
};

GraphWorld world_of(const ros_graph::RobotView& view, const sim::ItemCatalogue& catalogue, double now) {
  GraphWorld w;
  for (const auto& f : view.frames) {
    if (catalogue.find(f.child) != nullptr) {
      w.items[f.child] = Pose2{f.translation[0], f.translation[1], rotation_yaw(f.rotation)};
    } else if (f.child.rfind("touch", 0) == 0 && now - f.received < kTouchFreshS) {
      w.fingers.emplace_back(std::atoi(f.child.c_str() + 5), Vec2(f.translation[0], f.translation[1]));
    } else if (f.child == "arm_reach") {
      w.arm_reach = f.translation;
    }
  }
  for (const auto& m : view.footprints) {
    std::string name = m.frame;
    if (!name.empty() && name.front() == '/') name.erase(0, 1);
    Polygon2 polygon;
    for (std::size_t i = 0; i + 1 < m.points.size(); ++i) polygon.emplace_back(m.points[i][0], m.points[i][1]);
    if (polygon.size() >= 3) w.footprints[name] = std::move(polygon);
  }
  return w;
}

planning::MoveWorld move_world(const GraphWorld& w) {
  planning::MoveWorld world;
  world.item_centre = [&w](const std::string& item) -> std::optional<Vec2> {
    const auto it = w.items.find(item);
    if (it == w.items.end()) return std::nullopt;
    return it->second.position();
  };
  world.footprints = [&w] {
    std::vector<planning::Obstacle> out;
    for (const auto& [name, polygon] : w.footprints) {
      if (const auto it = w.items.find(name); it != w.items.end()) out.push_back({name, transformed(polygon, it->second)});
    }
    return out;
  };
  world.held_by_child = [&w](const std::string& item) { return w.touched(item); };
  return world;
}

std::vector<policies::ZoneObservation> zones_of(const ros_graph::RobotView& view) {
  std::vector<policies::ZoneObservation> out;
  for (const auto& m : view.zones) {
    policies::ZoneObservation z;
    z.colour = m.ns.substr(m.ns.rfind('_') + 1);  // sandbox_zone_blue → blue, as the play node
    for (std::size_t i = 0; i + 1 < m.points.size(); ++i) z.polygon.emplace_back(m.points[i][0], m.points[i][1]);
    if (z.polygon.size() < 3) continue;
    z.centroid = vertex_mean(z.polygon);
    out.push_back(std::move(z));
  }
  return out;
}

class RobotNode {
 public:
  explicit RobotNode(const RobotNodeOptions& options)
      : options_(options), catalogue_(*runner::SharedModels::shipped().catalogue),
        policy_(policies::make_policy(options.policy, options.policy_params)),
        executor_(std::shared_ptr<const planning::MotionPlanner>(planning::make_planner(options.planner)),
                  executor_config(options)),
        rng_(options.seed) {
    policies::PolicyContext context;
    for (const auto& item : catalogue_.items()) context.item_names.push_back(item.name);
    policy_->reset(context, Rng(SeedSequence(options.seed).seed_for("policy")));
  }

  RobotNodeStats run(const std::atomic<bool>& stop) {
    ros_graph::RobotGraph graph;
    graph_ = &graph;
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    for (long tick = 0;; ++tick) {
      const double t = static_cast<double>(tick) * kTickS;
      if (stop.load() || !graph.ok() || (options_.duration_s > 0 && t >= options_.duration_s)) break;
      std::this_thread::sleep_until(start + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(t)));
      step(t, graph.take());
    }
    graph_ = nullptr;
    return stats_;
  }

 private:
  static planning::MoveExecutorConfig executor_config(const RobotNodeOptions& o) {
    planning::MoveExecutorConfig config;
    config.time_budget_s = o.planner_budget_s;
    return config;
  }

  void step(double t, const ros_graph::RobotView& view) {
    const auto world = world_of(view, catalogue_, ros_graph::wall_now());
    const auto move = move_world(world);
    if (!world.items.empty()) {  // nothing to decide on before the game's TF arrives
      ++stats_.decisions;
      for (const auto& action : policy_->decide(observe(t, view, world))) handle(action, t, move);
    }
    if (executor_.status() == planning::MoveStatus::Running) {
      planning::MoveOutputs outputs;
      outputs.finger = [this](const planning::TimedPose& pose) {
        graph_->finger(pose.position.x(), pose.position.y());
        ++stats_.poses_sent;
      };
      executor_.step(kTickS, move, outputs);
      if (executor_.status() != planning::MoveStatus::Running) finish_move();
    }
    if (speaking_until_ >= 0 && t >= speaking_until_) {
      speaking_until_ = -1;
      policy_->on_result({policies::ActionResult::Kind::SpeechFinished, "", ""});
    }
  }

  policies::Observation observe(double t, const ros_graph::RobotView& view, const GraphWorld& world) const {
    policies::Observation o;
    o.t = t;
    for (const auto& [name, pose] : world.items) {
      policies::ItemObservation item;
      item.name = name;
      item.pose = pose;
      item.touched_by_child = world.touched(name);
      item.held_by_robot = executor_.status() == planning::MoveStatus::Running && current_item_ == name;
      o.items.push_back(std::move(item));
    }
    o.zones = zones_of(view);
    for (const auto& [n, p] : world.fingers) o.touches.push_back({n, p});
    o.interaction_events = view.interaction_events;
    if (policy_->perceives_children()) {  // face counts as the 2017 gazr nodes published them
      const char* seats[] = {"purple", "yellow"};
      for (std::size_t i = 0; i < 2; ++i) {
        if (view.faces[i] < 0) continue;
        policies::PerceivedChild child;
        child.seat = seats[i];
        child.face_detected = view.faces[i] > 0;
        o.children.push_back(std::move(child));
      }
    }
    if (world.arm_reach) {
      o.self.arm_reach_known = true;
      o.self.arm_reach_centre = {(*world.arm_reach)[0], (*world.arm_reach)[1]};
      o.self.arm_reach_radius = (*world.arm_reach)[2];
    }
    o.self.moving_item = executor_.status() == planning::MoveStatus::Running;
    o.self.current_item = current_item_;
    o.self.speaking = speaking_until_ >= 0;
    return o;
  }

  void handle(const policies::Action& action, double t, const planning::MoveWorld& move) {
    if (const auto* m = std::get_if<policies::MoveItem>(&action)) {
      current_item_ = m->item;
      ++stats_.moves_started;
      try {
        executor_.start({m->item, m->target}, move, rng_);
      } catch (const InputError& e) {
        spdlog::warn("policy '{}' asked for a bad move: {}", policy_->name(), e.what());
        ++stats_.moves_failed;
        policy_->on_result({policies::ActionResult::Kind::MoveFailed, m->item, e.what()});
        return;
      }
      spdlog::info("move {} to ({:.3f}, {:.3f})", m->item, m->target.x(), m->target.y());
      if (executor_.status() != planning::MoveStatus::Running) finish_move();
    } else if (const auto* look = std::get_if<policies::LookAt>(&action)) {
      if (look->point) graph_->look_at(look->point->x(), look->point->y(), look->point->z());
    } else if (const auto* point = std::get_if<policies::PointAt>(&action)) {
      graph_->point_at(point->point.x(), point->point.y());
    } else if (const auto* say = std::get_if<policies::Say>(&action)) {
      graph_->speech(say->text);
      speaking_until_ = t + kSpeechSPerChar * static_cast<double>(say->text.size());
    } else if (std::holds_alternative<policies::CancelMove>(action)) {
      executor_.cancel();
      if (executor_.status() == planning::MoveStatus::Preempted) finish_move();
    }
  }

  void finish_move() {
    const auto& outcome = executor_.current();
    policies::ActionResult result;
    result.item = current_item_;
    switch (outcome.status) {
      case planning::MoveStatus::Succeeded:
        result.kind = policies::ActionResult::Kind::MoveSucceeded;
        ++stats_.moves_succeeded;
        break;
      case planning::MoveStatus::Preempted: result.kind = policies::ActionResult::Kind::MoveCancelled; break;
      default:
        result.kind = policies::ActionResult::Kind::MoveFailed;
        result.reason = outcome.reason();
        ++stats_.moves_failed;
        spdlog::warn("move {} failed: {}", current_item_, outcome.reason());
        break;
    }
    policy_->on_result(result);
  }

  RobotNodeOptions options_;
  const sim::ItemCatalogue& catalogue_;
  std::unique_ptr<policies::PlayPolicy> policy_;
  planning::MoveExecutor executor_;
  Rng rng_;
  ros_graph::RobotGraph* graph_ = nullptr;
  std::string current_item_;
  double speaking_until_ = -1.0;
  RobotNodeStats stats_;
};

}  // namespace

RobotNodeStats run_robot_node(const RobotNodeOptions& options, const std::atomic<bool>& stop) {
  RobotNode node(options);  // bad policy or planner names fail before touching the graph
  std::string error;
  if (!ros_graph::start_ros(options.node_name, options.master_timeout_s, error)) throw std::runtime_error(error);
  return node.run(stop);
}

}  // namespace freeplay::ros_live
