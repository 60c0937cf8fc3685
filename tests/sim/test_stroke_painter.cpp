// The canvas stroker: coverage of round-capped, round-joined polylines, blended once per piece.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
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

// The painter's contract pixel by pixel: coverage a = clamp(width / 2 + 0.5 − d, 0, 1) from the centre's distance d
// to the nearest segment, as a byte, blended once.
cv::Mat painted_by_definition(const cv::Mat& image, const std::vector<cv::Point2d>& path, double width,
                              const cv::Vec3b& bgr) {
  cv::Mat out = image.clone();
  for (int y = 0; y < out.rows; ++y) {
    for (int x = 0; x < out.cols; ++x) {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k == 0 || k + 1 < path.size(); ++k) {
        const cv::Point2d a = path[k];
        const cv::Point2d ab = path[std::min(k + 1, path.size() - 1)] - a;
        const double length2 = ab.dot(ab);
        const double dx = x - a.x;
        const double dy = y - a.y;
        const double s = length2 > 0.0 ? std::clamp((dx * ab.x + dy * ab.y) / length2, 0.0, 1.0) : 0.0;
        const double ex = dx - s * ab.x;
        const double ey = dy - s * ab.y;
        nearest = std::min(nearest, std::sqrt(ex * ex + ey * ey));
      }
      const int a = static_cast<std::uint8_t>(255.0 * std::clamp(0.5 * width + 0.5 - nearest, 0.0, 1.0) + 0.5);
      auto& pixel = out.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) pixel[c] = static_cast<std::uint8_t>((pixel[c] * (255 - a) + bgr[c] * a + 127) / 255);
    }
  }
  return out;
}

TEST(StrokePainter, EveryPixelGetsTheCoverageOfItsDistanceToThePath) {
  // Random pieces as a child's finger draws them (short segments, some off the image), fractional and integer
  // coordinates, thin and wide strokes: every pixel as the definition says, the rims and the full interiors.
  Rng rng(42);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<cv::Point2d> path;
    const int points = static_cast<int>(rng.uniform_int(1, 8));
    cv::Point2d p(rng.uniform(-10.0, 70.0), rng.uniform(-10.0, 50.0));
    for (int i = 0; i < points; ++i) {
      if (trial % 3 == 0) p = cv::Point2d(std::round(p.x), std::round(p.y));
      path.push_back(p);
      p += cv::Point2d(rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0));
    }
    const double width = trial % 4 == 0 ? 1.0 + rng.uniform_int(0, 3) : rng.uniform(1.0, 30.0);
    const cv::Mat background(40, 60, CV_8UC3, cv::Scalar(200, 120, 30));
    cv::Mat image = background.clone();
    StrokePainter painter;
    painter.paint(image, path, width, kBlue);
    const cv::Mat expected = painted_by_definition(background, path, width, kBlue);
    EXPECT_EQ(cv::norm(image, expected, cv::NORM_INF), 0.0) << "trial " << trial << ", width " << width;
  }
}

TEST(StrokePainter, CanvasSizedPiecesMatchTheDefinitionAtEveryAngle) {
  // Pieces as the canvas paints them at 1920 px (50 px wide, 4 px samples), in every direction including exactly
  // and nearly axis-parallel ones (a slope below or near 1e-12): the rows' interval ends are computed with
  // reciprocals and two rows at a time, and every pixel must still be what the definition gives.
  Rng rng(7);
  for (int trial = 0; trial < 240; ++trial) {
    const double angle = trial % 4 == 0 ? (trial / 4 % 4) * 1.5707963267948966
                         : trial % 4 == 1 ? (trial / 4 % 4) * 1.5707963267948966 + rng.uniform(-1e-12, 1e-12)
                                          : rng.uniform(0.0, 6.283185307179586);
    cv::Point2d p(rng.uniform(20.0, 100.0), rng.uniform(20.0, 60.0));
    if (trial % 3 == 0) p = cv::Point2d(std::round(p.x), std::round(p.y));
    std::vector<cv::Point2d> path{p};
    const int segments = static_cast<int>(rng.uniform_int(1, 6));
    for (int i = 0; i < segments; ++i) {
      const double turn = trial % 4 < 2 ? 0.0 : rng.uniform(-0.3, 0.3);
      p += 4.0 * cv::Point2d(std::cos(angle + i * turn), std::sin(angle + i * turn));
      path.push_back(p);
    }
    const cv::Mat background(80, 120, CV_8UC3, cv::Scalar(200, 120, 30));
    cv::Mat image = background.clone();
    StrokePainter painter;
    painter.paint(image, path, 50.0, kBlue);
    const cv::Mat expected = painted_by_definition(background, path, 50.0, kBlue);
    EXPECT_EQ(cv::norm(image, expected, cv::NORM_INF), 0.0) << "trial " << trial << ", angle " << angle;
  }
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
