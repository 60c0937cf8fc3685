// Incremental zone rasters: the chamfer distances are OpenCV's, and windowed updates after random local edits give
// exactly the contours of the real node's whole-image OpenCV calls.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include <opencv2/imgproc.hpp>

#include "freeplay/sim/zone_raster.hpp"

namespace freeplay::sim::detail {
namespace {

constexpr int kWidth = 200;
constexpr int kHeight = 112;

/// Paints `count` random filled circles and rectangles of 0 or 255 (blobs of every size) into `mask`, inside `area`.
cv::Rect paint_blobs(cv::Mat& mask, std::mt19937& rng, int count, int max_radius) {
  std::uniform_int_distribution<int> x(-5, mask.cols + 5), y(-5, mask.rows + 5), r(1, max_radius), coin(0, 3);
  cv::Rect touched;
  for (int i = 0; i < count; ++i) {
    const cv::Point c(x(rng), y(rng));
    const int radius = r(rng);
    const cv::Scalar value(coin(rng) == 0 ? 0 : 255);
    if (coin(rng) % 2 == 0) {
      cv::circle(mask, c, radius, value, cv::FILLED, cv::LINE_8);
    } else {
      cv::rectangle(mask, cv::Rect(c.x - radius, c.y - radius / 2, 2 * radius, radius), value, cv::FILLED);
    }
    touched |= cv::Rect(c.x - radius - 1, c.y - radius - 1, 2 * radius + 3, 2 * radius + 3);
  }
  return touched;
}

TEST(ChamferDistances, AreOpenCvsDistanceTransform) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    cv::Mat mask(kHeight, kWidth, CV_8UC1, cv::Scalar(trial % 2 == 0 ? 0 : 255));
    paint_blobs(mask, rng, 1 + trial % 25, 4 + trial % 60);
    if (cv::countNonZero(mask) == static_cast<int>(mask.total())) mask.at<unsigned char>(trial % kHeight, 0) = 0;
    cv::Mat reference;
    cv::distanceTransform(mask, reference, cv::DIST_L2, cv::DIST_MASK_5);
    const auto distances = chamfer_distances(mask);
    for (int i = 0; i < static_cast<int>(mask.total()); ++i) {
      ASSERT_EQ(static_cast<float>(distances[static_cast<std::size_t>(i)]) * (1.0F / 65536.0F),
                reference.at<float>(i / kWidth, i % kWidth))
          << "trial " << trial << " pixel " << i;
    }
  }
}

// Searched in the box of the non-zero pixels, the contours and their tree are those of the whole image: few small
// blobs anywhere (borders and corners included), many large ones, a full image and an empty one.
TEST(ContoursOf, AreFindContoursOfTheWholeImage) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 300; ++trial) {
    const cv::Size size = trial % 3 == 2 ? cv::Size(203, 57) : cv::Size(kWidth, kHeight);  // rows of 8-byte words and not
    cv::Mat mask(size, CV_8UC1, cv::Scalar(trial == 0 ? 255 : 0));
    if (trial > 1) paint_blobs(mask, rng, 1 + trial % 12, 2 + trial % 45);
    Contours whole;
    std::vector<cv::Vec4i> whole_tree;
    cv::findContours(mask, whole, whole_tree, cv::RETR_TREE, cv::CHAIN_APPROX_TC89_KCOS);
    Contours boxed = {{cv::Point(1, 2)}};  // left over from an earlier call: replaced
    std::vector<cv::Vec4i> boxed_tree(3);
    contours_of(mask, boxed, boxed_tree);
    ASSERT_EQ(boxed, whole) << "trial " << trial;
    ASSERT_EQ(boxed_tree, whole_tree) << "trial " << trial;
  }
}

// Random local edits of every size, including masks that empty out or fill the whole image.
TEST(ColourRaster, WindowedUpdatesMatchTheWholeImagePipeline) {
  std::mt19937 rng(11);
  ColourRaster raster;
  raster.resize(cv::Size(kWidth, kHeight));
  ZoneSegmenterCounters work;
  cv::Mat mask(kHeight, kWidth, CV_8UC1, cv::Scalar(0));
  paint_blobs(mask, rng, 30, 40);
  mask.copyTo(raster.mask());
  raster.update(cv::Rect(0, 0, kWidth, kHeight), work);
  ASSERT_EQ(raster.contours(), reference_contours(mask));
  std::uniform_int_distribution<int> kind(0, 19);
  for (int step = 0; step < 600; ++step) {
    const int k = kind(rng);
    cv::Rect touched;
    if (k == 0) {
      mask.setTo(cv::Scalar(k % 2 == 0 ? 255 : 0));
      touched = cv::Rect(0, 0, kWidth, kHeight);
    } else if (k == 1) {
      mask.setTo(cv::Scalar(0));
      touched = cv::Rect(0, 0, kWidth, kHeight);
    } else {
      touched = paint_blobs(mask, rng, 1 + k % 3, k < 15 ? 6 : 30);
    }
    mask.copyTo(raster.mask());
    raster.update(touched, work);
    ASSERT_EQ(raster.contours(), reference_contours(mask)) << "step " << step << " kind " << k;
  }
  EXPECT_GT(work.rasters_windowed, 300u);
  EXPECT_LT(work.contour_searches, 600u);  // foregrounds that did not change are not searched again
}

}  // namespace
}  // namespace freeplay::sim::detail
