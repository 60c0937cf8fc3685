#include "freeplay/localisation/marker_field.hpp"

#include <algorithm>
#include <cmath>

#include "freeplay/core/error.hpp"
#include "freeplay/localisation/aruco.hpp"

namespace freeplay::localisation {
namespace {

constexpr double kScreenWidthM = 0.600;   // the screen picture spans the whole active area
constexpr double kScreenHeightM = 0.335;

/// A grid of equal rectangular cells in pixel units (pixel (c, r) covers [c, c+1) × [r, r+1)).
struct PixelGrid {
  double x0, y0;            ///< top-left corner
  double cell_w, cell_h;    ///< one cell's size
  cv::Mat values;           ///< CV_8UC1, one value per cell
};

double overlap(double a0, double a1, double b0, double b1) { return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)); }

/// Paints `grid` over `image` with exact area coverage: each pixel becomes the area-weighted mean of the cells
/// and the old picture it shows, so sub-pixel edges stay where they are and neighbouring cells leave no seams.
void paint(cv::Mat& image, const PixelGrid& grid, double opacity) {
  const double x1 = grid.x0 + grid.cell_w * grid.values.cols;
  const double y1 = grid.y0 + grid.cell_h * grid.values.rows;
  const int c0 = std::max(0, static_cast<int>(std::floor(grid.x0)));
  const int c1 = std::min(image.cols - 1, static_cast<int>(std::ceil(x1)) - 1);
  const int r0 = std::max(0, static_cast<int>(std::floor(grid.y0)));
  const int r1 = std::min(image.rows - 1, static_cast<int>(std::ceil(y1)) - 1);
  const int channels = image.channels();
  for (int r = r0; r <= r1; ++r) {
    auto* row = image.ptr<unsigned char>(r);
    const int i0 = std::max(0, static_cast<int>(std::floor((r - grid.y0) / grid.cell_h)));
    const int i1 = std::min(grid.values.rows - 1, static_cast<int>(std::floor((r + 1 - grid.y0) / grid.cell_h)));
    for (int c = c0; c <= c1; ++c) {
      const int j0 = std::max(0, static_cast<int>(std::floor((c - grid.x0) / grid.cell_w)));
      const int j1 = std::min(grid.values.cols - 1, static_cast<int>(std::floor((c + 1 - grid.x0) / grid.cell_w)));
      double cover = 0, paint_sum = 0;
      for (int i = i0; i <= i1; ++i) {
        const double oy = overlap(r, r + 1.0, grid.y0 + i * grid.cell_h, grid.y0 + (i + 1) * grid.cell_h);
        for (int j = j0; j <= j1; ++j) {
          const double a = oy * overlap(c, c + 1.0, grid.x0 + j * grid.cell_w, grid.x0 + (j + 1) * grid.cell_w);
          cover += a;
          paint_sum += a * grid.values.at<unsigned char>(i, j);
        }
      }
      cover *= opacity;
      paint_sum *= opacity;
      for (int k = 0; k < channels; ++k) {
        auto& px = row[c * channels + k];
        px = cv::saturate_cast<unsigned char>((1.0 - cover) * px + paint_sum);
      }
    }
  }
}

}  // namespace

std::optional<int> MarkerField::index_of(int marker_id) const {
  if (marker_id < first_id || marker_id >= first_id + count()) return std::nullopt;
  return marker_id - first_id;
}

std::array<Eigen::Vector3d, 4> MarkerField::corners(int index) const {
  const double left = origin_x_m + (index % columns) * pitch_m;
  const double top = -(origin_y_m + (index / columns) * pitch_m);  // rows go down the screen: towards −y
  return {Eigen::Vector3d(left, top, 0), Eigen::Vector3d(left + size_m, top, 0),
          Eigen::Vector3d(left + size_m, top - size_m, 0), Eigen::Vector3d(left, top - size_m, 0)};
}

MarkerField real_marker_field() { return {}; }

void draw_marker_field(cv::Mat& screen, const MarkerField& field) {
  if (screen.empty() || screen.depth() != CV_8U || (screen.channels() != 3 && screen.channels() != 1)) {
    throw InputError("screen image must be a non-empty 8-bit BGR or grey image", "screen image",
                     "CV_8UC3 (BGR) or CV_8UC1");
  }
  const double sx = screen.cols / kScreenWidthM;
  const double sy = screen.rows / kScreenHeightM;
  const cv::Mat white(1, 1, CV_8UC1, cv::Scalar(255));
  paint(screen, {0, 0, kFieldPictureWidthM * sx, kFieldPictureHeightM * sy, white}, kFieldBackgroundOpacity);
  for (int i = 0; i < field.count(); ++i) {
    const cv::Mat cells = marker_cells(field.id(i));
    const auto top_left = field.corners(i)[0];  // y: metres up from the screen's top edge (negative on screen)
    paint(screen, {top_left.x() * sx, -top_left.y() * sy, field.size_m / cells.cols * sx, field.size_m / cells.rows * sy, cells}, 1.0);
  }
}

}  // namespace freeplay::localisation
