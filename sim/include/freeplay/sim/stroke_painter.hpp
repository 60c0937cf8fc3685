#pragma once
// Anti-aliased strokes as an HTML/QML canvas `stroke()` paints them: the outline of the whole piece (round caps and
// joins) is filled once with each pixel's coverage, instead of a polygon and a round cap per polyline segment.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace freeplay::sim {

/// Paints round-capped, round-joined polylines into BGR images with anti-aliased coverage, reusing its buffers.
class StrokePainter {
 public:
  /// Paints `path` (pixel coordinates in `target`; integer coordinates are pixel centres, as OpenCV's) `width_px`
  /// wide in `bgr`: a pixel whose centre is d from the polyline gets coverage a = clamp(width_px / 2 + 0.5 − d, 0, 1)
  /// and becomes (1 − a) × itself + a × `bgr` (source-over, once per call). A one-point path paints a dot.
  void paint(cv::Mat& target, const std::vector<cv::Point2d>& path, double width_px, const cv::Vec3b& bgr);
  /// The same stroke as `destination-out` over `background` (same size as `target`): each pixel moves a of the way
  /// back to `background`'s pixel.
  void erase(cv::Mat& target, const cv::Mat& background, const std::vector<cv::Point2d>& path, double width_px);

 private:
  // Blends the stroke's coverage over `target` towards `source_of(y, x)`, a full-coverage run at once through
  // `source_of.copy_run(y, x, count, pixels)`.
  template <typename SourceOf>
  void blend(cv::Mat& target, const std::vector<cv::Point2d>& path, double width_px, const SourceOf& source_of);
  void cover(const std::vector<cv::Point2d>& path, double width_px, int cols, int rows);

  std::vector<std::uint8_t> coverage_;  // rows × cols of the last target, all 0 between calls
  std::vector<int> span_lo_;            // per row: first column with coverage (cols when none)
  std::vector<int> span_hi_;            // per row: last column with coverage (-1 when none)
  // One row of one segment's capsule: columns [x0, x1] covered at all, [f0, f1] fully (none when f0 > f1).
  struct RowRun {
    std::size_t segment;
    int y, x0, x1, f0, f1;
  };
  std::vector<RowRun> runs_;  // the last `cover`'s rows, in segment order
};

}  // namespace freeplay::sim
