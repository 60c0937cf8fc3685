#include "freeplay/ros/graph_messages.hpp"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "freeplay/core/sandtray_links.hpp"
#include "freeplay/planning/occupancy_grid.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/sim/markers.hpp"

namespace freeplay::ros_live {

namespace {

ros_graph::Polyline polyline(sim::LineMarker m) {
  return {std::move(m.frame), std::move(m.ns), m.id, std::move(m.points), m.rgb, m.width};
}

std::vector<ros_graph::Polyline> polylines(std::vector<sim::LineMarker> markers) {
  std::vector<ros_graph::Polyline> out;
  for (auto& m : markers) out.push_back(polyline(std::move(m)));
  return out;
}

}  // namespace

std::array<double, 4> yaw_rotation(double yaw) { return {0.0, 0.0, std::sin(yaw / 2), std::cos(yaw / 2)}; }

double rotation_yaw(const std::array<double, 4>& q) {
  return std::atan2(2.0 * (q[3] * q[2] + q[0] * q[1]), 1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]));
}

std::vector<ros_graph::Transform> game_frames(const sim::Sandtray& tray) {
  std::vector<ros_graph::Transform> out;
  for (const auto& item : tray.items()) {
    out.push_back({"sandtray", item.name, {item.pose.x, item.pose.y, 0.0}, yaw_rotation(item.pose.theta)});
  }
  for (const auto& touch : tray.touches()) {
    out.push_back({"sandtray", fmt::format("touch{}", touch.finger), {touch.position.x(), touch.position.y(), 0.0},
                   {0, 0, 0, 1}});
  }
  return out;
}

std::vector<ros_graph::Transform> camera_links() {
  std::vector<ros_graph::Transform> out;
  for (const auto& link : kSandtrayCameraLinks) {
    const auto q = link.rotation();
    out.push_back({"sandtray", link.frame, {link.xyz.x(), link.xyz.y(), link.xyz.z()}, {q.x(), q.y(), q.z(), q.w()}});
  }
  return out;
}

ros_graph::Transform arm_reach_frame(const runner::ReachDisc& reach) {
  return {"sandtray", "arm_reach", {reach.centre.x(), reach.centre.y(), reach.radius}, {0, 0, 0, 1}};
}

std::vector<ros_graph::Polyline> footprint_markers(const sim::Sandtray& tray) {
  return polylines(sim::footprint_markers(tray));
}

std::vector<ros_graph::Polyline> zone_markers(const sim::Sandtray& tray) { return polylines(sim::zone_markers(tray)); }

ros_graph::Image background_image(const sim::Sandtray& tray) {
  const cv::Mat& bgr = tray.background();
  ros_graph::Image image;
  image.width = bgr.cols;
  image.height = bgr.rows;
  image.pixel2meter = sim::kScreenWidthM / bgr.cols;
  cv::Mat rgba;
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  image.rgba.assign(rgba.data, rgba.data + rgba.total() * rgba.elemSize());
  cv::imencode(".png", bgr, image.png, {cv::IMWRITE_PNG_COMPRESSION, 3});  // png_level 3, as the launch file
  return image;
}

ros_graph::Grid occupancy_map(const sim::Sandtray& tray) {
  using planning::OccupancyGrid;
  const auto grid = OccupancyGrid::build(runner::sandtray_move_world(tray).footprints(), "");
  ros_graph::Grid out;
  out.width = OccupancyGrid::kCols;
  out.height = OccupancyGrid::kRows;
  out.resolution = OccupancyGrid::kResolutionM;
  out.origin_y = -OccupancyGrid::kHeightM;
  out.cells.resize(static_cast<std::size_t>(out.width * out.height));
  for (int row = 0; row < out.height; ++row) {  // OccupancyGrid rows run along −y; ROS rows start at origin_y
    for (int col = 0; col < out.width; ++col) {
      out.cells[static_cast<std::size_t>((out.height - 1 - row) * out.width + col)] =
          static_cast<std::int8_t>(grid.occupancy({col, row}));
    }
  }
  return out;
}

}  // namespace freeplay::ros_live
