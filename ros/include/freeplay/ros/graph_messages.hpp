#pragma once
// The simulated game as the graph's plain messages: the game's TF frames, footprints, zones, background image and
// the planner's occupancy map, plus the URDF camera links of `sandtray_publisher`.

#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/ros/graph.hpp"
#include "freeplay/runner/robot_body.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::ros_live {

/// Rotation about z by `yaw` as (qx, qy, qz, qw).
std::array<double, 4> yaw_rotation(double yaw);
/// The yaw of a rotation (qx, qy, qz, qw).
double rotation_yaw(const std::array<double, 4>& q);
/// The game's TF broadcaster: sandtray → every item (centre, yaw) and touch1…touch6 while a finger is down.
std::vector<ros_graph::Transform> game_frames(const sim::Sandtray& tray);
/// sandtray_publisher (sandtray.xacro, kSandtrayCameraLinks): sandtray → the camera links.
std::vector<ros_graph::Transform> camera_links();
/// sandtray_localisation's `arm_reach` frame: shoulder projected on the table, z = radius of the reachable disc.
ros_graph::Transform arm_reach_frame(const runner::ReachDisc& reach);
/// The game's FootprintsPublisher (sim::footprint_markers) as the graph's polylines.
std::vector<ros_graph::Polyline> footprint_markers(const sim::Sandtray& tray);
/// zones_from_image (sim::zone_markers) as the graph's polylines.
std::vector<ros_graph::Polyline> zone_markers(const sim::Sandtray& tray);
/// The game's ImagePublisher: the background (drawing included) as rgba8 and PNG.
ros_graph::Image background_image(const sim::Sandtray& tray);
/// map_and_plan's `/map`: the occupancy grid of every footprint (nothing inhibited).
ros_graph::Grid occupancy_map(const sim::Sandtray& tray);

}  // namespace freeplay::ros_live
