// The only file of the project that touches cv::aruco (its API changed in OpenCV 4.7).
#include "freeplay/localisation/aruco.hpp"

#include <fmt/format.h>

#include <opencv2/core/version.hpp>
#include <opencv2/imgproc.hpp>

#if CV_VERSION_MAJOR > 4 || (CV_VERSION_MAJOR == 4 && CV_VERSION_MINOR >= 7)
#define FREEPLAY_ARUCO_DETECTOR_API 1  // cv::aruco::ArucoDetector, generateImageMarker, Dictionary by value
#include <opencv2/objdetect/aruco_detector.hpp>
#else
#include <opencv2/aruco.hpp>
#endif

#include "freeplay/core/error.hpp"

namespace freeplay::localisation {
namespace {

constexpr int kBorderBits = 1;
constexpr int kMarkerBits = 5;  // DICT_ARUCO_ORIGINAL: 5 × 5 data bits, 1024 ids

}  // namespace

int marker_dictionary_size() { return 1024; }

cv::Mat marker_cells(int id) {
  if (id < 0 || id >= marker_dictionary_size()) {
    throw InputError(fmt::format("marker id {} is not in the ArUco original dictionary", id), "marker id",
                     fmt::format("0 to {}", marker_dictionary_size() - 1));
  }
  cv::Mat cells;
  const int side = kMarkerBits + 2 * kBorderBits;  // one pixel per cell
  const auto dictionary = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_ARUCO_ORIGINAL);
#ifdef FREEPLAY_ARUCO_DETECTOR_API
  cv::aruco::generateImageMarker(dictionary, id, side, cells, kBorderBits);
#else
  cv::aruco::drawMarker(dictionary, id, side, cells, kBorderBits);
#endif
  return cells;
}

std::vector<MarkerDetection> detect_markers(const cv::Mat& image) {
  if (image.empty() || image.depth() != CV_8U || (image.channels() != 3 && image.channels() != 1)) {
    throw InputError("camera image must be a non-empty 8-bit colour or grey image", "image", "CV_8UC3, CV_8UC1");
  }
  cv::Mat grey;
  if (image.channels() == 3) {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  } else {
    grey = image;
  }
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
#ifdef FREEPLAY_ARUCO_DETECTOR_API
  cv::aruco::DetectorParameters parameters;
  parameters.cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  const cv::aruco::ArucoDetector detector(cv::aruco::getPredefinedDictionary(cv::aruco::DICT_ARUCO_ORIGINAL),
                                          parameters);
  detector.detectMarkers(grey, corners, ids);
#else
  auto parameters = cv::aruco::DetectorParameters::create();
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  cv::aruco::detectMarkers(grey, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_ARUCO_ORIGINAL), corners, ids,
                           parameters);
#endif
  std::vector<MarkerDetection> out(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    out[i].id = ids[i];
    for (std::size_t k = 0; k < 4; ++k) out[i].corners[k] = corners[i][k];
  }
  return out;
}

}  // namespace freeplay::localisation
