#pragma once
// `freeplay robot`: a freeplay play policy, the planner and the move_sandbox_items executor as a node of a live ROS 1
// sandtray (the real QML game with its core nodes, or `freeplay serve --robot external`). The policy's Observation
// is built from the graph and its actions go out as `/poses` fake touches, `speech`, and gaze / pointing targets.

#include <yaml-cpp/yaml.h>

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "freeplay/planning/planner_settings.hpp"

namespace freeplay::ros_live {

/// Settings of the robot node.
struct RobotNodeOptions {
  std::string policy = "asocial";       ///< registered policy name
  YAML::Node policy_params;             ///< its parameters
  std::string planner = planning::PlannerSettings{}.name;  ///< motion planner
  /// Planning budget per move (s).
  double planner_budget_s = planning::kDefaultTimeBudgetS;
  std::uint64_t seed = 1;               ///< the policy's and planner's random streams
  double duration_s = 0.0;              ///< stop after this many seconds (0: until stopped)
  std::string node_name = "freeplay_robot";  ///< ros::init name
  double master_timeout_s = 10.0;       ///< how long to wait for the ROS master
};

/// What the node did.
struct RobotNodeStats {
  int decisions = 0;        ///< policy ticks
  int moves_started = 0;    ///< MoveItem actions executed
  int moves_succeeded = 0;  ///< moves whose last pose was sent
  int moves_failed = 0;     ///< moves refused, unplannable or stopped
  int poses_sent = 0;       ///< `/poses` messages published
};

/// Runs the node at 10 Hz until `stop`, the duration or ROS shutdown; throws std::runtime_error without a master
/// and InputError for an unknown policy or planner.
RobotNodeStats run_robot_node(const RobotNodeOptions& options, const std::atomic<bool>& stop);

}  // namespace freeplay::ros_live
