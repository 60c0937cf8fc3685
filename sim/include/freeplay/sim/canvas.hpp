#pragma once
// The game's drawing layer: the background plus children's 50 px strokes in the Tango palette (and the eraser).

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "freeplay/core/geometry.hpp"
#include "freeplay/sim/background.hpp"
#include "freeplay/sim/changed_pixels.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/sim/stroke_painter.hpp"

namespace freeplay::sim {

/// Background + strokes at one raster resolution (the image the game publishes on `/sandtray/background/image`).
class DrawingCanvas {
 public:
  /// An empty canvas on the blank background, `width_px` wide (height follows the 0.6 × 0.335 m aspect).
  explicit DrawingCanvas(int width_px = kScreenWidthPx);

  /// Replaces the background and clears every stroke.
  void set_background(BackgroundKind kind);
  /// Starts stroke `stroke_id` in `colour` at `p` (sandtray metres); throws InputError when 6 strokes are active.
  void begin_stroke(int stroke_id, PaletteColour colour, const Vec2& p);
  /// Extends an active stroke to `p`, smoothing with a quadratic curve between midpoints; throws on unknown id.
  void extend_stroke(int stroke_id, const Vec2& p);
  /// Finishes an active stroke (draws its last half segment); unknown ids are ignored.
  void end_stroke(int stroke_id);
  /// Removes every stroke (the bare background remains); active strokes go on from their current point.
  void clear_strokes();

  /// Background + strokes, BGR CV_8UC3.
  const cv::Mat& image() const { return image_; }
  /// The bare background.
  const cv::Mat& background_image() const { return background_; }
  /// Which background is shown.
  BackgroundKind background_kind() const { return kind_; }
  /// True when the image changed since the last mark_published().
  bool dirty() const { return dirty_; }
  /// Records that the current image was published.
  void mark_published() {
    dirty_ = false;
    unpublished_.clear();
  }
  /// Bounding box of every pixel changed since the last mark_published() (empty when none).
  const cv::Rect& unpublished_rect() const { return unpublished_.box(); }
  /// Every pixel changed since the last mark_published(), row by row.
  const ChangedPixels& unpublished() const { return unpublished_; }
  /// Fraction of pixels that differ from the bare background (0…1).
  double coverage() const;
  /// 64-bit hash of the image pixels (and background kind); equal images give equal hashes.
  std::uint64_t hash() const;
  /// Number of strokes being drawn now.
  std::size_t active_strokes() const { return strokes_.size(); }
  /// Raster width (pixels).
  int width_px() const { return image_.cols; }
  /// Stroke width at this raster width (50 px at 1920 px).
  int stroke_width_px() const { return stroke_width_px_; }
  /// Pixel position (sub-pixel) of a sandtray point at this raster width.
  cv::Point2d to_pixel(const Vec2& p) const;

 private:
  struct Stroke {
    PaletteColour colour;
    cv::Point2d last_point;  // last input point (pixels)
    cv::Point2d last_mid;    // end of what is drawn so far (pixels)
  };
  void paint_path(const std::vector<cv::Point2d>& path, PaletteColour colour);
  void touch(const cv::Rect& changed);

  BackgroundKind kind_ = BackgroundKind::Blank;
  cv::Mat background_;
  cv::Mat image_;
  int stroke_width_px_;
  std::map<int, Stroke> strokes_;
  bool dirty_ = true;
  ChangedPixels unpublished_;
  mutable std::optional<std::uint64_t> hash_cache_;
  StrokePainter painter_;                // paints each smoothed piece once (anti-aliased coverage)
  std::vector<cv::Point2d> piece_;       // the samples of the piece being painted
  std::vector<cv::Point2d> local_path_;  // the same relative to its rectangle
};

/// Fraction of pixels where two BGR CV_8UC3 images of one size differ (a drawing's coverage of its background).
double differing_pixel_share(const cv::Mat& image, const cv::Mat& background);

}  // namespace freeplay::sim
