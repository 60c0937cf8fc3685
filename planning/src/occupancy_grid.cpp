#include "freeplay/planning/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace freeplay::planning {

namespace {
constexpr unsigned char kFreePixel = 255;
constexpr unsigned char kCoveredPixel = 0;
// Guards floor() against 0.3 / 0.005 = 59.999… style rounding.
constexpr double kCellEpsilon = 1e-9;
}  // namespace

OccupancyGrid::OccupancyGrid() : occupancy_(static_cast<std::size_t>(kCols) * kRows, kFree) {}

OccupancyGrid OccupancyGrid::build(const std::vector<Obstacle>& obstacles, std::string_view inhibited) {
  // Image rows are cell rows (row 0 at y = 0), so no vertical flip is needed and no row offset can creep in.
  cv::Mat image(kRows, kCols, CV_8UC1, cv::Scalar(kFreePixel));
  std::vector<cv::Point> points;
  for (const auto& obstacle : obstacles) {
    if (obstacle.name == inhibited || obstacle.footprint.size() < 3) continue;
    points.clear();
    for (const auto& v : obstacle.footprint) {
      const Cell c = cell_of(v);
      points.emplace_back(c.col, c.row);
    }
    cv::fillConvexPoly(image, points, cv::Scalar(kCoveredPixel));
  }
  cv::blur(image, image, cv::Size(3, 3));
  OccupancyGrid grid;
  for (int row = 0; row < kRows; ++row) {
    const auto* pixels = image.ptr<unsigned char>(row);
    for (int col = 0; col < kCols; ++col) {
      grid.occupancy_[index({col, row})] = kOccupied - pixels[col] * kOccupied / kFreePixel;
    }
  }
  return grid;
}

Cell OccupancyGrid::cell_of(const Vec2& p) {
  return {static_cast<int>(std::floor(p.x() / kResolutionM + kCellEpsilon)),
          static_cast<int>(std::floor(-p.y() / kResolutionM + kCellEpsilon))};
}

Vec2 OccupancyGrid::cell_point(const Cell& c) { return {c.col * kResolutionM, -c.row * kResolutionM}; }

Cell OccupancyGrid::clamp(const Cell& c) {
  return {std::clamp(c.col, 0, kCols - 1), std::clamp(c.row, 0, kRows - 1)};
}

double OccupancyGrid::outside_step_cost(const Cell& c) const {
  const Cell edge = clamp(c);
  const double distance = std::hypot(c.col - edge.col, c.row - edge.row);
  return occupancy(edge) + 1.0 + kOutsideCostPerCell * distance;
}

void OccupancyGrid::set_occupancy(const Cell& c, int value) {
  occupancy_.at(index(clamp(c))) = std::clamp(value, kFree, kOccupied);
}

}  // namespace freeplay::planning
