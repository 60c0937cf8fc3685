#pragma once
// Which pixels of an image changed since some moment: their bounding box and, row by row, the changed columns.

#include <vector>

#include <opencv2/core.hpp>

namespace freeplay::sim {

/// The pixels of an image changed since some moment (a canvas's unpublished strokes): every changed pixel lies in
/// `box` and, in its row, in that row's columns; other pixels are unchanged.
class ChangedPixels {
 public:
  /// Nothing changed in an image of `rows` rows.
  explicit ChangedPixels(int rows = 0) : rows_(static_cast<std::size_t>(rows), cv::Range(0, 0)) {}

  /// Marks every pixel of `rect` (clipped to the image's rows) as changed.
  void add(const cv::Rect& rect) {
    if (rect.empty()) return;
    box_ = box_.empty() ? rect : (box_ | rect);
    const int end_row = std::min(rect.y + rect.height, static_cast<int>(rows_.size()));
    for (int y = std::max(rect.y, 0); y < end_row; ++y) {
      cv::Range& columns = rows_[static_cast<std::size_t>(y)];
      columns = columns.empty() ? cv::Range(rect.x, rect.x + rect.width)
                                : cv::Range(std::min(columns.start, rect.x), std::max(columns.end, rect.x + rect.width));
    }
  }
  /// Nothing changed any more.
  void clear() {
    const int end_row = std::min(box_.y + box_.height, static_cast<int>(rows_.size()));
    for (int y = std::max(box_.y, 0); y < end_row; ++y) rows_[static_cast<std::size_t>(y)] = cv::Range(0, 0);
    box_ = {};
  }
  /// Rows of the image.
  int row_count() const { return static_cast<int>(rows_.size()); }
  /// Bounding box of the changed pixels (empty when none).
  const cv::Rect& box() const { return box_; }
  /// The changed columns [start, end) of row `y` (empty when none); `y` in [0, rows).
  cv::Range columns(int y) const { return rows_[static_cast<std::size_t>(y)]; }

 private:
  cv::Rect box_;
  std::vector<cv::Range> rows_;
};

}  // namespace freeplay::sim
