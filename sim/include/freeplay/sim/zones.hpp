#pragma once
// Colour zones of the background (the real `zones_from_image` node): HSV ranges → polygons in `sandtray`.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "freeplay/core/geometry.hpp"
#include "freeplay/sim/changed_pixels.hpp"

namespace freeplay::sim {

/// One colour region of the background (one LINE_STRIP marker of the real `zones` topic).
struct Zone {
  std::string colour;  ///< zone name = colour ("green", "blue", …), marker ns `sandbox_zone_<colour>`
  int id = 0;          ///< 0.. per colour, in contour order
  Polygon2 polygon;    ///< contour in the `sandtray` frame (m; y ≤ 0), not closed
  Vec2 centroid;       ///< vertex mean (what the play policy uses)
  double area_m2 = 0;  ///< enclosed area (m², absolute value)
};

/// The zone colours, in the order the real node processes them.
inline constexpr std::array<std::string_view, 7> kZoneColours = {"green", "blue",   "yellow", "white",
                                                                 "black", "purple", "red"};

/// An inclusive HSV range (OpenCV units: H 0–179, S and V 0–255).
struct HsvRange {
  std::array<int, 3> lower;  ///< (H, S, V) lower bound
  std::array<int, 3> upper;  ///< (H, S, V) upper bound
};

/// The real node's HSV range of a zone colour; throws InputError listing kZoneColours when unknown.
HsvRange zone_hsv_range(std::string_view colour);
/// Marker colour of a zone (HSV-range midpoint converted to RGB, as the real node does).
std::array<unsigned char, 3> zone_marker_rgb(std::string_view colour);
/// Width the real node downsamples the image to before segmenting (pixels).
inline constexpr int kZoneSegmentationWidthPx = 200;

/// Counts of the work a ZoneSegmenter did (for tests and benchmarks).
struct ZoneSegmenterCounters {
  std::uint64_t images = 0;            ///< images segmented
  std::uint64_t images_recalled = 0;   ///< whole images whose HSV conversion this thread had made before: reused
  std::uint64_t masks_recomputed = 0;  ///< colour masks segmented (new to this segmenter and its thread's memo)
  std::uint64_t masks_reused = 0;      ///< colour masks unchanged since the last image, or seen before: reused
  std::uint64_t rasters_full = 0;      ///< colour pipelines recomputed on the whole image
  std::uint64_t rasters_windowed = 0;  ///< colour pipelines updated only around the changed pixels
  std::uint64_t contour_searches = 0;  ///< contour searches (only when a colour's foreground changed)
  std::uint64_t distance_pixels = 0;   ///< pixels whose distance to the colour's border was recomputed
};

class ZoneSegmenter;
namespace detail {
class ColourRaster;

/// Blocks of a bilinear downsampling that a resize of their own source block gives exactly as the whole resize does.
struct ResizeTiles {
  int band_rows = 0;  ///< rows of the downsampled image per band (its height when no band resizes alone)
  int tile_cols = 0;  ///< columns per tile; a run of whole tiles resizes alone too (its width when none does)
};

/// The tiles of downsampling `source` to `small` (OpenCV INTER_LINEAR), checked once per thread and size on a random
/// image against the whole resize.
ResizeTiles resize_tiles(const cv::Size& source, const cv::Size& small);
}  // namespace detail

/// The zones of one background image (immutable once built).
class ZoneMap {
 public:
  /// No zones.
  ZoneMap() = default;
  /// Segments a BGR CV_8UC3 image with the real pipeline (the real node's OpenCV calls on the whole image: the
  /// reference ZoneSegmenter matches); `metres_per_pixel` of the full-resolution image. Throws InputError on an empty
  /// image, another type, or a non-positive scale.
  static ZoneMap segment(const cv::Mat& bgr, double metres_per_pixel);

  /// Every zone, colour by colour in kZoneColours order, ids ascending.
  const std::vector<Zone>& zones() const { return zones_; }
  /// Zones of one colour; throws InputError listing kZoneColours when the colour is unknown.
  std::vector<const Zone*> of_colour(std::string_view colour) const;
  /// The zone containing `p` (the smallest if several), nullptr if none.
  const Zone* at(const Vec2& p) const;
  /// Number of zones of a colour; throws InputError listing kZoneColours when the colour is unknown.
  std::size_t count(std::string_view colour) const;

 private:
  friend class ZoneSegmenter;
  /// Appends one colour's zones from its contours (small-image pixels × scale = full-image pixels) in metres.
  void add_zones(std::string_view colour, const std::vector<std::vector<cv::Point>>& contours, double scale_x,
                 double scale_y, double metres_per_pixel);
  std::vector<Zone> zones_;
};

/// Segments a sequence of backgrounds, redoing a colour's morphology, distance transform and contours only when
/// that colour's mask changed since the previous image (a stroke changes a few of the seven masks), and
/// then only around the changed pixels; a whole new background reuses the masks its thread segmented recently. The
/// zones are identical to ZoneMap::segment's.
class ZoneSegmenter {
 public:
  /// Counts of the work done so far.
  using Counters = ZoneSegmenterCounters;
  ZoneSegmenter();
  ~ZoneSegmenter();
  ZoneSegmenter(const ZoneSegmenter&) = delete;
  ZoneSegmenter& operator=(const ZoneSegmenter&) = delete;

  /// Same checks and result as ZoneMap::segment. With `changed`, the caller promises that `bgr` differs from the
  /// previous image only inside that rectangle, and only those pixels are converted to HSV again; a `changed` that
  /// covers the whole image marks a new background, whose conversion this thread keeps and recalls when it recurs.
  ZoneMap segment(const cv::Mat& bgr, double metres_per_pixel, std::optional<cv::Rect> changed = std::nullopt);
  /// The same, told row by row which pixels differ from the previous image (an image of `bgr`'s rows): only those
  /// are converted again, and only the tiles of the downsampled image that read them are resized.
  ZoneMap segment(const cv::Mat& bgr, double metres_per_pixel, const ChangedPixels& changed);
  /// Work done so far.
  const Counters& counters() const { return counters_; }

 private:
  /// Both public segments: `rows`, when given, narrows `changed` row by row.
  ZoneMap segment_changes(const cv::Mat& bgr, double metres_per_pixel, std::optional<cv::Rect> changed,
                          const ChangedPixels* rows);
  /// The columns of row `y` converted again: `region`'s, narrowed to the row's changed ones when `rows` is given.
  static cv::Range converted_columns(int y, const cv::Rect& region, const ChangedPixels* rows);
  /// Converts the pixels of `bgr` that the bilinear downsampling reads (inside `region`, narrowed by `rows`) into hsv_.
  void convert_rows(const cv::Mat& bgr, const cv::Rect& region, const ChangedPixels* rows);
  /// Writes every colour's mask inside `region` of small_hsv_; returns each colour's changed bounding box.
  std::array<cv::Rect, kZoneColours.size()> update_masks(const cv::Rect& region);

  std::array<std::unique_ptr<detail::ColourRaster>, kZoneColours.size()> rasters_;
  cv::Mat hsv_;                 // full-size HSV image; only the rows the downsampling reads are kept up to date
  bool hsv_shared_ = false;     // hsv_ is a recalled conversion, shared with the thread's memo: copied before writes
  std::vector<char> needed_;    // rows of hsv_ the downsampling reads
  cv::Mat small_hsv_;           // the downsampled HSV image
  cv::Mat previous_small_;      // the one before (the masks change only where they differ), except in resized_
  cv::Rect resized_;            // the part of small_hsv_ the last call resized (there previous_small_ is not updated yet)
  detail::ResizeTiles tiles_;   // blocks of small_hsv_ that a resize of their own source block gives exactly
  Counters counters_;
};

}  // namespace freeplay::sim
