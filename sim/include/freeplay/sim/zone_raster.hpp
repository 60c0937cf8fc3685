#pragma once
// One zone colour's raster pipeline (the real node's opening, dilation, distance transform, threshold and contours)
// kept up to date incrementally: a change of the colour mask inside a rectangle recomputes only the pixels that
// rectangle can reach, with results identical to running the OpenCV calls on the whole mask.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "freeplay/sim/zones.hpp"

namespace freeplay::sim::detail {

/// Contours in small-image pixels, as cv::findContours returns them.
using Contours = std::vector<std::vector<cv::Point>>;

/// The real node's mask → contour steps with OpenCV on the whole mask (opening, dilation, distance transform,
/// threshold at a quarter of its maximum, dilation, contours): the reference the incremental pipeline matches.
Contours reference_contours(const cv::Mat& mask);

/// cv::findContours(binary, contours, hierarchy, RETR_TREE, CHAIN_APPROX_TC89_KCOS) of a CV_8UC1 image, searched only
/// in the box of its non-zero pixels: the same contours in the same order.
void contours_of(const cv::Mat& binary, Contours& contours, std::vector<cv::Vec4i>& hierarchy);

/// Chamfer distances (OpenCV's 5×5 L2 mask in 16.16 fixed point) of every pixel of a CV_8UC1 image to its nearest
/// zero pixel; as cv::distanceTransform(DIST_L2, DIST_MASK_5) computes them before scaling (for tests).
std::vector<std::uint32_t> chamfer_distances(const cv::Mat& binary);

/// Work counters of the raster updates (rasters_full, rasters_windowed, contour_searches, distance_pixels).
using ColourRasterWork = ZoneSegmenterCounters;

/// One colour's mask and everything derived from it, updated in place.
class ColourRaster {
 public:
  /// The colour mask (CV_8UC1, 0 or 255); write new values into it, then call update() with their bounding box.
  cv::Mat& mask() { return mask_; }
  /// The colour mask.
  const cv::Mat& mask() const { return mask_; }
  /// Sizes the mask (all zero) and forgets everything derived; the next update must cover the whole image.
  void resize(cv::Size size);
  /// Brings the derived rasters and contours up to date after the mask changed, only inside `changed`.
  void update(const cv::Rect& changed, ColourRasterWork& work);
  /// Contours of the current mask (identical to reference_contours(mask())).
  const Contours& contours() const { return contours_; }
  /// The mask was rewritten as a whole and its contours are known (a memo): keeps them, recomputes the rest later.
  void adopt(const Contours& contours);

 private:
  void recompute_all(ColourRasterWork& work);
  /// Distances after the dilated mask changed inside `moved`; returns the window recomputed.
  cv::Rect update_distances(const cv::Rect& moved, ColourRasterWork& work);
  /// Largest distance of each row in [first_row, end_row), then of the image.
  void refresh_row_maxima(int first_row, int end_row);
  /// Threshold and dilation inside `window` (grown by 2 for the dilation); true when the foreground changed.
  bool refresh_foreground(const cv::Rect& window);
  void find_contours(ColourRasterWork& work);

  cv::Mat mask_;      // the colour mask
  cv::Mat eroded_;    // scratch: 5×5 erosion of mask_ (valid only where last computed)
  cv::Mat opened_;    // scratch: opening of mask_ (valid only where last computed)
  cv::Mat next_;      // scratch: new values of one step before they are compared
  cv::Mat dilated_;   // dilation of the opening: the distance transform's input
  cv::Mat core_;      // distance above a quarter of the maximum (before the last dilation)
  cv::Mat foreground_;// what the contours are found in
  std::vector<std::uint32_t> distance_;  // chamfer distances of dilated_ (16.16 fixed point)
  std::vector<std::uint32_t> window_;    // scratch for one windowed distance pass (with a 2-pixel ring)
  std::vector<unsigned char> scratch_;   // scratch for the separable filters
  std::vector<std::uint32_t> row_max_;   // largest distance of each row
  std::uint32_t max_distance_ = 0;
  int nonzero_ = 0;           // non-zero pixels of dilated_
  bool valid_ = false;        // derived rasters match mask_ (and distance_ is exact)
  bool distance_valid_ = false;
  Contours contours_;
  std::vector<cv::Vec4i> hierarchy_;
};

}  // namespace freeplay::sim::detail
