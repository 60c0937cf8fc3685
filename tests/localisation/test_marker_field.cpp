// The marker field: the real layout and id order, the ArUco stand-in dictionary, its drawing on the screen
// (found again by the detector, at the right pixels), and the game's 5 s display.

#include <gtest/gtest.h>

#include <algorithm>

#include "freeplay/core/error.hpp"
#include "freeplay/localisation/aruco.hpp"
#include "freeplay/localisation/marker_field.hpp"

namespace freeplay::localisation {
namespace {

TEST(MarkerField, HasTheRealLayoutAndIdOrder) {
  const MarkerField field = real_marker_field();
  EXPECT_EQ(field.count(), 15);
  EXPECT_EQ(field.id(0), 700);
  EXPECT_EQ(field.id(14), 714);
  EXPECT_EQ(field.index_of(707), 7);
  EXPECT_FALSE(field.index_of(699).has_value());
  EXPECT_FALSE(field.index_of(715).has_value());
  // 700 top-left at (60, −25) mm; 704 ends the first row; 714 is bottom-right; 80 mm squares.
  EXPECT_TRUE(field.corners(0)[0].isApprox(Eigen::Vector3d(0.060, -0.025, 0)));
  EXPECT_TRUE(field.corners(4)[1].isApprox(Eigen::Vector3d(0.540, -0.025, 0)));
  EXPECT_TRUE(field.corners(5)[0].isApprox(Eigen::Vector3d(0.060, -0.125, 0)));
  EXPECT_TRUE(field.corners(14)[2].isApprox(Eigen::Vector3d(0.540, -0.305, 0)));
  EXPECT_NEAR((field.corners(3)[1] - field.corners(3)[0]).norm(), 0.080, 1e-12);
  EXPECT_NEAR((field.corners(3)[3] - field.corners(3)[0]).norm(), 0.080, 1e-12);
}

TEST(MarkerField, TheArucoDictionaryHoldsTheRealIds) {
  EXPECT_GE(marker_dictionary_size(), 715);
  const cv::Mat cells = marker_cells(714);
  ASSERT_EQ(cells.rows, 7);
  ASSERT_EQ(cells.cols, 7);
  for (int k = 0; k < 7; ++k) {  // the black border
    EXPECT_EQ(cells.at<unsigned char>(0, k), 0);
    EXPECT_EQ(cells.at<unsigned char>(6, k), 0);
    EXPECT_EQ(cells.at<unsigned char>(k, 0), 0);
    EXPECT_EQ(cells.at<unsigned char>(k, 6), 0);
  }
  EXPECT_GT(cv::countNonZero(cells), 0);
  EXPECT_THROW(marker_cells(1024), InputError);
  EXPECT_THROW(marker_cells(-1), InputError);
}

TEST(MarkerField, DrawnFieldIsFoundWithEveryIdWhereItWasDrawn) {
  cv::Mat screen(1080, 1920, CV_8UC3, cv::Scalar(68, 190, 115));
  draw_marker_field(screen);
  const auto detections = detect_markers(screen);
  ASSERT_EQ(detections.size(), 15U);
  const MarkerField field = real_marker_field();
  const double sx = 1920 / 0.600, sy = 1080 / 0.335;
  std::vector<int> ids;
  for (const auto& d : detections) {
    ids.push_back(d.id);
    const auto index = field.index_of(d.id);
    ASSERT_TRUE(index.has_value()) << d.id;
    const auto corners = field.corners(*index);
    for (std::size_t k = 0; k < 4; ++k) {
      // pixel centres sit at integers: a corner at x metres is at x·s − 0.5 px
      EXPECT_NEAR(d.corners[k].x, corners[k].x() * sx - 0.5, 1.0) << d.id << " corner " << k;
      EXPECT_NEAR(d.corners[k].y, -corners[k].y() * sy - 0.5, 1.0) << d.id << " corner " << k;
    }
  }
  std::sort(ids.begin(), ids.end());
  for (int i = 0; i < 15; ++i) EXPECT_EQ(ids[static_cast<std::size_t>(i)], 700 + i);
}

TEST(MarkerField, WhiteBackgroundAtEightyPercentOverTheTopThirtyThreeCentimetres) {
  cv::Mat screen(1072, 1920, CV_8UC1, cv::Scalar(100));
  draw_marker_field(screen);
  EXPECT_EQ(screen.at<unsigned char>(5, 5), 224);         // 0.2 · 100 + 0.8 · 255 between the markers
  EXPECT_EQ(screen.at<unsigned char>(1071, 1000), 100);   // below 0.33 m the game shows through untouched
  EXPECT_EQ(screen.at<unsigned char>(90, 195), 0);        // inside marker 700's black border
  EXPECT_THROW({ cv::Mat empty; draw_marker_field(empty); }, InputError);
}

TEST(MarkerDisplay, ShowsForFiveSecondsAfterEachSignal) {
  MarkerDisplay display;
  EXPECT_FALSE(display.showing(0.0));
  display.on_signal(10.0);
  EXPECT_FALSE(display.showing(9.9));
  EXPECT_TRUE(display.showing(10.0));
  EXPECT_TRUE(display.showing(14.9));
  EXPECT_FALSE(display.showing(15.0));
  display.on_signal(20.0);  // shown again on the next signal
  EXPECT_TRUE(display.showing(24.0));
  EXPECT_FALSE(display.showing(25.0));
}

}  // namespace
}  // namespace freeplay::localisation
