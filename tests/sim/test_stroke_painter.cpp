// The canvas stroker: coverage of round-capped, round-joined polylines, blended once per piece.

#include <gtest/gtest.h>

#include <cmath>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/stroke_painter.hpp"

namespace freeplay::sim {
namespace {

const cv::Vec3b kWhite(255, 255, 255);
const cv::Vec3b kBlue(164, 101, 52);

cv::Mat white(int cols, int rows) { return cv::Mat(rows, cols, CV_8UC3, cv::Scalar(255, 255, 255)); }

TEST(StrokePainter, ADotCoversPixelsByTheirCentresDistance) {
  StrokePainter painter;
  cv::Mat image = white(60, 60);
  painter.paint(image, {{30.0, 30.0}}, 25.0, kBlue);
  EXPECT_EQ(image.at<cv::Vec3b>(30, 30), kBlue);  // centre
  EXPECT_EQ(image.at<cv::Vec3b>(30, 42), kBlue);  // 12 px: coverage 12.5 + 0.5 − 12 = 1
  EXPECT_EQ(image.at<cv::Vec3b>(30, 44), kWhite);  // 14 px: outside
  // 12.5 px away: coverage one half.
  cv::Mat half = white(60, 60);
  painter.paint(half, {{30.0, 30.5}}, 25.0, kBlue);
  const cv::Vec3b rim = half.at<cv::Vec3b>(43, 30);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rim[c], (255 + kBlue[c]) / 2.0, 1.0) << c;
}

TEST(StrokePainter, OverlappingSegmentsAreBlendedOnceLikeACanvasStroke) {
  // A path that doubles back over itself paints the pixels of a single pass: coverage is the union's, not a sum.
  StrokePainter painter;
  cv::Mat once = white(120, 60);
  cv::Mat twice = white(120, 60);
  painter.paint(once, {{20.0, 30.0}, {60.0, 30.5}, {100.0, 29.0}}, 25.0, kBlue);
  painter.paint(twice, {{20.0, 30.0}, {60.0, 30.5}, {100.0, 29.0}, {60.0, 30.5}, {20.0, 30.0}}, 25.0, kBlue);
  EXPECT_EQ(cv::norm(once, twice, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(once.reshape(1) != 255), 0);
}

TEST(StrokePainter, EraserRestoresTheBackgroundAndLeavesNoCoverageBehind) {
  StrokePainter painter;
  const cv::Mat background(40, 80, CV_8UC3, cv::Scalar(10, 200, 30));
  cv::Mat image = background.clone();
  painter.paint(image, {{10.0, 20.0}, {70.0, 20.0}}, 11.0, kBlue);
  ASSERT_GT(cv::norm(image, background, cv::NORM_INF), 0.0);
  painter.erase(image, background, {{5.0, 20.0}, {75.0, 20.0}}, 25.0);  // wider than the stroke: all of it goes
  EXPECT_EQ(cv::norm(image, background, cv::NORM_INF), 0.0);
  // The coverage buffer is clean again: the same stroke paints the same pixels on a fresh image.
  cv::Mat a = white(80, 40);
  cv::Mat b = white(80, 40);
  painter.paint(a, {{10.0, 20.0}, {70.0, 22.0}}, 11.0, kBlue);
  painter.paint(b, {{10.0, 20.0}, {70.0, 22.0}}, 11.0, kBlue);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(StrokePainter, ClipsToTheTargetAndRejectsOtherImageTypes) {
  StrokePainter painter;
  cv::Mat image = white(30, 30);
  painter.paint(image, {{-5.0, 15.0}, {40.0, 15.0}}, 9.0, kBlue);  // runs off both sides
  EXPECT_EQ(image.at<cv::Vec3b>(15, 0), kBlue);
  EXPECT_EQ(image.at<cv::Vec3b>(15, 29), kBlue);
  EXPECT_EQ(image.at<cv::Vec3b>(0, 15), kWhite);
  cv::Mat grey(10, 10, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(painter.paint(grey, {{5.0, 5.0}}, 3.0, kBlue), InputError);
  cv::Mat small = white(5, 5);
  EXPECT_THROW(painter.erase(image, small, {{5.0, 5.0}}, 3.0), InputError);
}

}  // namespace
}  // namespace freeplay::sim
