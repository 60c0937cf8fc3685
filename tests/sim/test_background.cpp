// Backgrounds: sizes, colours at known places, map description loading and its errors.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <opencv2/core.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/background.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::sim {
namespace {

cv::Vec3b rgb_at(const cv::Mat& bgr, const Vec2& p) {
  const double mpp = kScreenWidthM / bgr.cols;
  const cv::Vec3b v = bgr.at<cv::Vec3b>(static_cast<int>(-p.y() / mpp), static_cast<int>(p.x() / mpp));
  return {v[2], v[1], v[0]};
}

TEST(Background, SizeFollowsTheAspect) {
  for (const auto kind : {BackgroundKind::Blank, BackgroundKind::FreeplayMap, BackgroundKind::Tutorial}) {
    const cv::Mat image = render_background(kind, kScreenWidthPx);
    EXPECT_EQ(image.cols, kScreenWidthPx);
    EXPECT_EQ(image.rows, kScreenHeightPx);
    EXPECT_EQ(image.type(), CV_8UC3);
  }
  EXPECT_EQ(render_background(BackgroundKind::FreeplayMap, 600).rows, 335);
  EXPECT_EQ(raster_height(1920), 1072);
}

TEST(Background, BlankIsBlack) {
  const cv::Mat image = render_background(BackgroundKind::Blank, 320);
  EXPECT_EQ(cv::countNonZero(image.reshape(1)), 0);
}

TEST(Background, MapHasTheTangoColoursWhereTheReferenceSaysSo) {
  const cv::Mat map = render_background(BackgroundKind::FreeplayMap, kScreenWidthPx);
  EXPECT_EQ(rgb_at(map, {0.09, -0.06}), cv::Vec3b(0xee, 0xee, 0xec));  // castle courtyard, top-left
  EXPECT_EQ(rgb_at(map, {0.08, -0.30}), cv::Vec3b(0x34, 0x65, 0xa4));  // lake, bottom-left
  EXPECT_EQ(rgb_at(map, {0.56, -0.03}), cv::Vec3b(0xfc, 0xe9, 0x4f));  // savanna, top-right
  EXPECT_EQ(rgb_at(map, {0.56, -0.30}), cv::Vec3b(0x00, 0x80, 0x00));  // forest, bottom-right
  EXPECT_EQ(rgb_at(map, {0.37, -0.28}), cv::Vec3b(0x73, 0xd2, 0x16));  // grass
}

TEST(Background, TutorialIsWhiteWithFourRings) {
  const cv::Mat tutorial = render_background(BackgroundKind::Tutorial, kScreenWidthPx);
  EXPECT_EQ(rgb_at(tutorial, {0.5, -0.3}), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(rgb_at(tutorial, {0.103, -0.080}), cv::Vec3b(255, 255, 255));         // ring centre is empty
  EXPECT_EQ(rgb_at(tutorial, {0.103 + 0.0251, -0.080}), cv::Vec3b(0xef, 0x29, 0x29));  // red ring outline
  EXPECT_EQ(rgb_at(tutorial, {0.295 + 0.0251, -0.089}), cv::Vec3b(0x73, 0xd2, 0x16));  // green
  EXPECT_EQ(rgb_at(tutorial, {0.152 + 0.0251, -0.224}), cv::Vec3b(0x34, 0x65, 0xa4));  // blue
  EXPECT_EQ(rgb_at(tutorial, {0.315 + 0.0251, -0.216}), cv::Vec3b(0xfc, 0xe9, 0x4f));  // yellow
}

TEST(Background, RenderingIsDeterministic) {
  const cv::Mat a = render_background(BackgroundKind::FreeplayMap, 960);
  const cv::Mat b = render_background(BackgroundKind::FreeplayMap, 960);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(Background, BadWidthIsAnInputError) {
  EXPECT_THROW(render_background(BackgroundKind::FreeplayMap, 0), InputError);
  EXPECT_THROW(render_background(BackgroundKind::Blank, -5), InputError);
  EXPECT_THROW(render_background(BackgroundKind::Blank, 100000), InputError);
}

TEST(Background, NamesRoundTrip) {
  for (const auto kind : {BackgroundKind::Blank, BackgroundKind::FreeplayMap, BackgroundKind::Tutorial}) {
    EXPECT_EQ(background_from_name(background_name(kind)), kind);
  }
  EXPECT_FALSE(background_from_name("moon").has_value());
}

class MapFile : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& text) {
    path_ = std::filesystem::temp_directory_path() /
            ("freeplay_map_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml");
    std::ofstream(path_) << text;
    return path_;
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::filesystem::path path_;
};

TEST_F(MapFile, LoadsAndRendersShapes) {
  const auto map = MapDescription::load(write(
      "size: [100, 50]\nbackground: \"#000000\"\nshapes:\n"
      "  - {type: polygon, fill: \"#ff0000\", points: [[0, 0], [50, 0], [50, 50], [0, 50]]}\n"
      "  - {type: ellipse, fill: \"#00ff00\", centre: [75, 25], radii: [10, 10]}\n"));
  ASSERT_EQ(map.shapes.size(), 2u);
  const cv::Mat image = render_map(map, 200);
  EXPECT_EQ(image.rows, 112);
  EXPECT_EQ(image.at<cv::Vec3b>(50, 40), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(image.at<cv::Vec3b>(50, 150), cv::Vec3b(0, 255, 0));
  EXPECT_EQ(image.at<cv::Vec3b>(5, 195), cv::Vec3b(0, 0, 0));
}

TEST_F(MapFile, BadColourNamesFileLineAndKey) {
  const auto path = write("size: [100, 50]\nbackground: \"#000000\"\nshapes:\n"
                          "  - {type: polygon, fill: \"red\", points: [[0, 0], [50, 0], [50, 50]]}\n");
  try {
    MapDescription::load(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "shapes[0].fill");
    EXPECT_EQ(e.where().line, 4);
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos);
  }
}

TEST_F(MapFile, UnknownShapeTypeListsTheAllowedOnes) {
  const auto path = write("size: [100, 50]\nbackground: \"#000000\"\nshapes:\n  - {type: star, fill: \"#ffffff\"}\n");
  try {
    MapDescription::load(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "shapes[0].type");
    EXPECT_EQ(e.allowed(), "polygon, ellipse, polyline");
  }
}

TEST_F(MapFile, MissingSizeAndUnknownKeysAreRejected) {
  EXPECT_THROW(MapDescription::load(write("background: \"#000000\"\n")), InputError);
  EXPECT_THROW(MapDescription::load(write("size: [1, 1]\nbackground: \"#000000\"\ncolour: 3\n")), InputError);
  EXPECT_THROW(MapDescription::load(write("size: [1, 1]\nbackground: \"#000000\"\nshapes:\n"
                                          "  - {type: polyline, stroke: \"#ffffff\", width: -1, points: [[0,0],[1,1]]}\n")),
               InputError);
}

}  // namespace
}  // namespace freeplay::sim
