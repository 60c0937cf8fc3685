// Screen image: items where their pose says (position, rotation sense, z order, visibility), stash, palette,
// touches, robot hand, zone outlines, item pictures and bad input.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/background.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/screen_renderer.hpp"

namespace freeplay::sim {
namespace {

class Screen : public ::testing::Test {
 protected:
  Screen() : catalogue_(ItemCatalogue::load_default()), renderer_(catalogue_) {}

  cv::Mat render(const std::vector<ItemView>& items, ScreenOverlay overlay = {}, int width = kScreenWidthPx) {
    return renderer_.render(map_, items, overlay, width);
  }
  ItemView view(const std::string& name, Pose2 pose, int z = 0) { return {&catalogue_.get(name), pose, z, true}; }
  static cv::Point pixel(const Vec2& p, int width = kScreenWidthPx) {
    const double mpp = kScreenWidthM / width;
    return {static_cast<int>(std::lround(p.x() / mpp)), static_cast<int>(std::lround(-p.y() / mpp))};
  }
  /// Number of pixels differing between two images inside `box`.
  static int differing(const cv::Mat& a, const cv::Mat& b, const cv::Rect& box) {
    cv::Mat diff;
    cv::absdiff(a(box), b(box), diff);
    cv::Mat grey;
    cv::cvtColor(diff, grey, cv::COLOR_BGR2GRAY);
    return cv::countNonZero(grey);
  }
  /// Centroid of the pixels that differ from a uniform background.
  static cv::Point2d changed_centroid(const cv::Mat& image, const cv::Vec3b& background) {
    cv::Mat mask;
    cv::inRange(image, cv::Scalar(background[0], background[1], background[2]),
                cv::Scalar(background[0], background[1], background[2]), mask);
    cv::bitwise_not(mask, mask);
    const cv::Moments m = cv::moments(mask, true);
    return {m.m10 / m.m00, m.m01 / m.m00};
  }

  ItemCatalogue catalogue_;
  ScreenRenderer renderer_;
  cv::Mat map_ = render_background(BackgroundKind::FreeplayMap, kScreenWidthPx);
};

TEST_F(Screen, SizeFollowsTheWidth) {
  EXPECT_EQ(render({}).size(), cv::Size(1920, 1072));
  EXPECT_EQ(render({}, {}, 960).size(), cv::Size(960, 536));
  EXPECT_EQ(render({}, {}, 4000).size(), cv::Size(4000, 2233));
}

TEST_F(Screen, ItemIsDrawnWhereItsPoseSays) {
  ScreenOverlay no_stash;
  no_stash.stash_visible = false;
  const cv::Mat empty = render({}, no_stash);
  const Vec2 a(0.2, -0.2), b(0.4, -0.1);
  const cv::Mat at_a = render({view("hippo", {a.x(), a.y(), 0.0})}, no_stash);
  const cv::Mat at_b = render({view("hippo", {b.x(), b.y(), 0.0})}, no_stash);
  const cv::Rect box_a(pixel(a) - cv::Point(40, 40), cv::Size(80, 80));
  const cv::Rect box_b(pixel(b) - cv::Point(40, 40), cv::Size(80, 80));
  EXPECT_NE(at_a.at<cv::Vec3b>(pixel(a)), empty.at<cv::Vec3b>(pixel(a)));
  EXPECT_GT(differing(at_a, empty, box_a), 80 * 80 / 2);
  EXPECT_EQ(differing(at_a, empty, box_b), 0);
  EXPECT_GT(differing(at_b, empty, box_b), 80 * 80 / 2);
  EXPECT_EQ(differing(at_b, empty, box_a), 0);
  // Nothing is drawn outside the item's box (side 0.0506 m = 162 px, rotated bound ≤ 229 px).
  cv::Mat outside = at_a.clone();
  empty(cv::Rect(pixel(a) - cv::Point(116, 116), cv::Size(232, 232)))
      .copyTo(outside(cv::Rect(pixel(a) - cv::Point(116, 116), cv::Size(232, 232))));
  EXPECT_EQ(cv::norm(outside, empty, cv::NORM_INF), 0.0);
}

TEST_F(Screen, ThetaIsCounterClockwiseOnTheScreen) {
  const cv::Vec3b magenta(255, 0, 255);
  const cv::Mat plain(kScreenHeightPx, kScreenWidthPx, CV_8UC3, cv::Scalar(magenta[0], magenta[1], magenta[2]));
  ScreenOverlay no_stash;
  no_stash.stash_visible = false;
  const Vec2 centre(0.3, -0.17);
  const cv::Point2d c(pixel(centre));
  const auto offset = [&](double theta) {
    const cv::Mat image = renderer_.render(plain, {view("giraffe", {centre.x(), centre.y(), theta})}, no_stash,
                                           kScreenWidthPx);
    return changed_centroid(image, magenta) - c;
  };
  const cv::Point2d upright = offset(0.0);
  ASSERT_GT(cv::norm(upright), 3.0);  // the picture's mass is off-centre: rotations move it
  const cv::Point2d quarter = offset(std::numbers::pi / 2);
  // A counter-clockwise quarter turn on a y-down screen maps (dx, dy) to (dy, −dx).
  EXPECT_NEAR(quarter.x, upright.y, 1.5);
  EXPECT_NEAR(quarter.y, -upright.x, 1.5);
}

TEST_F(Screen, HigherZIsOnTop) {
  const Pose2 pose{0.3, -0.2, 0.0};
  const cv::Point centre = pixel({pose.x, pose.y});
  const cv::Vec3b ball_alone = render({view("ball", pose)}).at<cv::Vec3b>(centre);
  const cv::Vec3b hippo_alone = render({view("hippo", pose)}).at<cv::Vec3b>(centre);
  ASSERT_NE(ball_alone, hippo_alone);
  EXPECT_EQ(render({view("hippo", pose, 1), view("ball", pose, 2)}).at<cv::Vec3b>(centre), ball_alone);
  EXPECT_EQ(render({view("hippo", pose, 3), view("ball", pose, 2)}).at<cv::Vec3b>(centre), hippo_alone);
  EXPECT_EQ(render({view("ball", pose, 2), view("hippo", pose, 1)}).at<cv::Vec3b>(centre), ball_alone);
}

TEST_F(Screen, HiddenItemsAreSkipped) {
  ItemView hidden = view("girl", {0.2, -0.2, 0.0});
  hidden.visible = false;
  EXPECT_EQ(cv::norm(render({hidden}), render({}), cv::NORM_INF), 0.0);
}

TEST_F(Screen, StashStripOnTheRight) {
  const cv::Mat with = render({});
  EXPECT_EQ(with.at<cv::Vec3b>(500, 1900), cv::Vec3b(0x11, 0x11, 0x11));
  EXPECT_EQ(with.at<cv::Vec3b>(500, 1696), cv::Vec3b(0x11, 0x11, 0x11));  // x ≥ 0.88 W ≈ 1690, border 5 px
  EXPECT_GT(with.at<cv::Vec3b>(500, 1690)[0], 0x11);                      // the lighter left border
  EXPECT_EQ(with.at<cv::Vec3b>(500, 1680), map_.at<cv::Vec3b>(500, 1680));
  ScreenOverlay none;
  none.stash_visible = false;
  EXPECT_EQ(render({}, none).at<cv::Vec3b>(500, 1900), map_.at<cv::Vec3b>(500, 1900));
}

TEST_F(Screen, PaletteOnTheLeftWhenDrawingIsOn) {
  ScreenOverlay drawing;
  drawing.palette_visible = true;
  const cv::Mat image = render({}, drawing);
  const int top = (kScreenHeightPx - (4 * 60 + 80)) / 2;
  const auto rgb = [&](int x, int y) {
    const cv::Vec3b v = image.at<cv::Vec3b>(y, x);
    return std::array<unsigned char, 3>{v[2], v[1], v[0]};
  };
  EXPECT_EQ(rgb(30, top + 30), palette_rgb(PaletteColour::Yellow));
  EXPECT_EQ(rgb(90, top + 30), palette_rgb(PaletteColour::Orange));
  EXPECT_EQ(rgb(30, top + 210), palette_rgb(PaletteColour::Red));
  EXPECT_EQ(rgb(90, top + 210), palette_rgb(PaletteColour::White));
  EXPECT_EQ(cv::norm(render({})(cv::Rect(0, 0, 200, top)), image(cv::Rect(0, 0, 200, top)), cv::NORM_INF), 0.0);
}

TEST_F(Screen, TouchesAndRobotHandAreMarked) {
  ScreenOverlay overlay;
  overlay.touches = {{0.1, -0.3}, {0.2, -0.3}};
  overlay.robot_hand = Vec2(0.4, -0.3);
  const cv::Mat marked = render({}, overlay);
  const cv::Mat bare = render({});
  for (const Vec2& p : {Vec2(0.1, -0.3), Vec2(0.2, -0.3), Vec2(0.4, -0.3)}) {
    EXPECT_NE(marked.at<cv::Vec3b>(pixel(p)), bare.at<cv::Vec3b>(pixel(p)));
  }
}

TEST_F(Screen, ZoneOutlinesAndLabels) {
  const ZoneMap zones = ZoneMap::segment(map_, kMetresPerPixel);
  cv::Mat outlined = map_.clone();
  draw_zones(outlined, zones, false);
  cv::Mat labelled = map_.clone();
  draw_zones(labelled, zones, true);
  const cv::Rect all(0, 0, map_.cols, map_.rows);
  const int outline_pixels = differing(outlined, map_, all);
  EXPECT_GT(outline_pixels, 1000);
  EXPECT_GT(differing(labelled, map_, all), outline_pixels);
  // A vertex of the lake's outline is drawn.
  const Zone* lake = zones.at({0.08, -0.30});
  ASSERT_NE(lake, nullptr);
  EXPECT_NE(outlined.at<cv::Vec3b>(pixel(lake->polygon.front())), map_.at<cv::Vec3b>(pixel(lake->polygon.front())));
}

TEST_F(Screen, EveryItemHasItsOwnPicture) {
  std::vector<cv::Mat> pictures;
  for (const ItemSpec& spec : catalogue_.items()) {
    const cv::Mat picture = item_picture(spec, 128);
    ASSERT_EQ(picture.type(), CV_8UC4) << spec.name;
    ASSERT_EQ(picture.size(), cv::Size(128, 128));
    std::vector<cv::Mat> channels;
    cv::split(picture, channels);
    const double opaque = cv::countNonZero(channels[3]) / (128.0 * 128.0);
    EXPECT_GT(opaque, 0.15) << spec.name;
    EXPECT_LT(opaque, 0.9) << spec.name;
    EXPECT_EQ(channels[3].at<unsigned char>(0, 0), 0) << spec.name;  // transparent corner
    for (const cv::Mat& other : pictures) EXPECT_GT(cv::norm(picture, other, cv::NORM_L1), 0.0) << spec.name;
    pictures.push_back(picture);
  }
  EXPECT_THROW(draw_item_picture(catalogue_.items().front(), 0), InputError);
}

TEST_F(Screen, AnItemsPngPictureIsFittedIntoItsSquareAndAnUnreadableOneIsDrawn) {
  const auto dir = std::filesystem::temp_directory_path() / ("freeplay-picture-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // 40 × 20: the left half opaque orange, the right half half-transparent blue (BGRA).
  cv::Mat png(20, 40, CV_8UC4, cv::Scalar(0x3e, 0xaf, 0xfc, 255));
  png(cv::Rect(20, 0, 20, 20)).setTo(cv::Scalar(0xa4, 0x65, 0x34, 128));
  ASSERT_TRUE(cv::imwrite((dir / "wide.png").string(), png));
  std::ofstream(dir / "not-a.png") << "not a PNG";
  ItemSpec spec = catalogue_.items().front();
  spec.picture = (dir / "wide.png").string();  // an absolute path stays itself under the assets folder
  const cv::Mat picture = item_picture(spec, 64);
  ASSERT_EQ(picture.type(), CV_8UC4);
  ASSERT_EQ(picture.size(), cv::Size(64, 64));
  EXPECT_EQ(picture.at<cv::Vec4b>(32, 10), cv::Vec4b(0x3e, 0xaf, 0xfc, 255));  // fitted to 64 × 32, centred
  EXPECT_EQ(picture.at<cv::Vec4b>(32, 54), cv::Vec4b(0xa4, 0x65, 0x34, 128));
  EXPECT_EQ(picture.at<cv::Vec4b>(10, 32)[3], 0);  // above the fitted picture: transparent
  EXPECT_EQ(picture.at<cv::Vec4b>(54, 32)[3], 0);
  spec.picture = (dir / "not-a.png").string();
  EXPECT_EQ(cv::norm(item_picture(spec, 64), draw_item_picture(spec, 64), cv::NORM_INF), 0.0);
  std::filesystem::remove_all(dir);
}

TEST_F(Screen, RenderingIsDeterministic) {
  const std::vector<ItemView> items = {view("zebra", {0.1, -0.1, 0.4}, 1), view("lion", {0.3, -0.2, -2.0}, 2)};
  EXPECT_EQ(cv::norm(render(items), render(items), cv::NORM_INF), 0.0);
}

TEST_F(Screen, BadInputIsAnInputError) {
  EXPECT_THROW(render({}, {}, 0), InputError);
  EXPECT_THROW(render({}, {}, 20000), InputError);
  EXPECT_THROW(renderer_.render(cv::Mat(), {}, {}, 640), InputError);
  EXPECT_THROW(renderer_.render(cv::Mat(10, 10, CV_8UC1), {}, {}, 640), InputError);
  EXPECT_THROW(render({view("ball", {std::nan(""), -0.1, 0.0})}), InputError);
  cv::Mat grey(10, 10, CV_8UC1);
  EXPECT_THROW(draw_zones(grey, ZoneMap(), true), InputError);
}

}  // namespace
}  // namespace freeplay::sim
