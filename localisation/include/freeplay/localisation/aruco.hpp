#pragma once
// The one adapter to OpenCV's ArUco module (it stands in for chilitags, which OpenCV cannot read): marker bit
// patterns and detection. OpenCV 4.7 moved these functions into cv::aruco::ArucoDetector; only aruco.cpp knows.

#include <array>
#include <opencv2/core.hpp>
#include <vector>

namespace freeplay::localisation {

/// One marker found in an image: its id and its four corners (px; top-left, top-right, bottom-right,
/// bottom-left of the marker as printed).
struct MarkerDetection {
  int id = -1;                          ///< dictionary id
  std::array<cv::Point2f, 4> corners;  ///< sub-pixel corners
};

/// Ids the dictionary (DICT_ARUCO_ORIGINAL) holds: 0 to this − 1.
int marker_dictionary_size();

/// The cells of marker `id`, black border included: a 7 × 7 CV_8UC1 matrix, 0 black, 255 white, row 0 on top.
/// Throws InputError for an id outside the dictionary.
cv::Mat marker_cells(int id);

/// Every dictionary marker visible in `image` (BGR, RGB or grey 8-bit), corners refined to sub-pixel accuracy.
std::vector<MarkerDetection> detect_markers(const cv::Mat& image);

}  // namespace freeplay::localisation
