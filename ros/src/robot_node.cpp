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
#include "freeplay/runner/robot_side.hpp"

namespace freeplay::ros_live {

namespace {

constexpr double kTickS = 0.1;             // decision and /poses rate (10 Hz)
constexpr double kTouchFreshS = 0.35;      // a touchN frame older than this is a lifted finger (the game sends 10 Hz)

/// The yaw of a rotation (qx, qy, qz, qw).
double rotation_yaw(const std::array<double, 4>& q) {
  return std::atan2(2.0 * (q[3] * q[2] + q[0] * q[1]), 1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]));
}

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

// The graph as the robot side's world: `/poses` fake touches, speech, gaze and pointing targets go out on the graph.
class GraphActuators final : public runner::RobotWorld {
 public:
  GraphActuators(ros_graph::RobotGraph& graph, RobotNodeStats& stats) : graph_(graph), stats_(stats) {}

  /// The sandtray as the graph showed it at this tick.
  void update(GraphWorld world) { world_ = std::move(world); }
  const GraphWorld& world() const { return world_; }

  planning::MoveWorld move_world() override { return ros_live::move_world(world_); }
  void move_started(const policies::MoveItem& move, bool running, double /*t*/) override {
    spdlog::info("move {} to ({:.3f}, {:.3f}){}", move.item, move.target.x(), move.target.y(),
                 running ? "" : ": not started");
  }
  void finger(const planning::TimedPose& pose, double /*t*/) override {
    graph_.finger(pose.position.x(), pose.position.y());
    ++stats_.poses_sent;
  }
  void move_ended(const policies::MoveItem& move, planning::MoveStatus status, events::MoveResult result,
                  double /*t*/) override {
    if (status == planning::MoveStatus::Succeeded || status == planning::MoveStatus::Preempted) return;
    spdlog::warn("move {} failed: {}", move.item, result.reason);
  }
  void look_at(const policies::LookAt& look, double /*t*/) override {
    // A child's face: where the seat puts it (the robot node has no head tracker of its own).
    const Eigen::Vector3d p = look.child ? runner::seat_face(*look.child) : look.point.value_or(Eigen::Vector3d::Zero());
    if (look.child || look.point) graph_.look_at(p.x(), p.y(), p.z());
  }
  void point_at(const Vec2& point, double /*t*/) override { graph_.point_at(point.x(), point.y()); }
  void say(const std::string& text, const std::string& /*to*/, double /*duration_s*/, double /*t*/) override {
    graph_.speech(text);
  }
  void cancel(double /*t*/) override { spdlog::info("move cancelled"); }

 private:
  ros_graph::RobotGraph& graph_;
  RobotNodeStats& stats_;
  GraphWorld world_;
};

class RobotNode {
 public:
  explicit RobotNode(const RobotNodeOptions& options)
      : options_(options), catalogue_(*runner::SharedModels::shipped().catalogue),
        robot_(make_policy(options, catalogue_), make_executor(options), Rng(options.seed), runner::BadMove::Report) {}

  RobotNodeStats run(const std::atomic<bool>& stop) {
    ros_graph::RobotGraph graph;
    GraphActuators actuators(graph, stats_);
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    for (long tick = 0;; ++tick) {
      const double t = static_cast<double>(tick) * kTickS;
      if (stop.load() || !graph.ok() || (options_.duration_s > 0 && t >= options_.duration_s)) break;
      std::this_thread::sleep_until(start + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(t)));
      graph.maintain();
      const auto view = graph.take();
      actuators.update(world_of(view, catalogue_, ros_graph::wall_now()));
      if (actuators.world().items.empty()) continue;  // nothing to decide on before the game's TF arrives
      ++stats_.decisions;
      auto o = observe(t, view, actuators.world());
      robot_.step(t, o, actuators);
    }
    const auto& m = robot_.counts();
    stats_.moves_started = m.moves_started;
    stats_.moves_succeeded = m.moves_succeeded;
    stats_.moves_failed = m.moves_failed;
    return stats_;
  }

 private:
  static std::unique_ptr<policies::PlayPolicy> make_policy(const RobotNodeOptions& o,
                                                           const sim::ItemCatalogue& catalogue) {
    auto policy = policies::make_policy(o.policy, o.policy_params);
    policies::PolicyContext context;
    for (const auto& item : catalogue.items()) context.item_names.push_back(item.name);
    policy->reset(context, Rng(SeedSequence(o.seed).seed_for("policy")));
    return policy;
  }

  static std::unique_ptr<planning::MoveExecutor> make_executor(const RobotNodeOptions& o) {
    planning::MoveExecutorConfig config;
    config.time_budget_s = o.planner_budget_s;
    return std::make_unique<planning::MoveExecutor>(
        std::shared_ptr<const planning::MotionPlanner>(planning::make_planner(o.planner)), config);
  }

  policies::Observation observe(double t, const ros_graph::RobotView& view, const GraphWorld& world) const {
    policies::Observation o;
    o.t = t;
    for (const auto& [name, pose] : world.items) {
      policies::ItemObservation item;
      item.name = name;
      item.pose = pose;
      item.touched_by_child = world.touched(name);
      item.held_by_robot = robot_.moving() && robot_.current_item() == name;
      o.items.push_back(std::move(item));
    }
    o.zones = zones_of(view);
    for (const auto& [n, p] : world.fingers) o.touches.push_back({n, p});
    o.interaction_events = view.interaction_events;
    if (robot_.perceives_children()) {  // face counts as the 2017 gazr nodes published them
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
    o.self.speaking = robot_.speaking(t);
    return o;
  }

  RobotNodeOptions options_;
  const sim::ItemCatalogue& catalogue_;
  runner::RobotSide robot_;
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
