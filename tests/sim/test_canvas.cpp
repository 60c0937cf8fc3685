// Drawing layer: pixel ↔ metre mapping, stroke width, smoothing, eraser, dirty flag, coverage, hash, limits.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/canvas.hpp"

namespace freeplay::sim {
namespace {

cv::Vec3b bgr(PaletteColour colour) {
  const auto rgb = palette_rgb(colour);
  return {rgb[2], rgb[1], rgb[0]};
}

TEST(Palette, NamesAndTangoColours) {
  EXPECT_EQ(palette_name(PaletteColour::Yellow), "yellow");
  EXPECT_EQ(palette_from_name("purple"), PaletteColour::Purple);
  EXPECT_EQ(palette_from_name("eraser"), PaletteColour::Eraser);
  EXPECT_FALSE(palette_from_name("magenta").has_value());
  EXPECT_EQ(palette_rgb(PaletteColour::Blue), (std::array<unsigned char, 3>{0x34, 0x65, 0xa4}));
  EXPECT_EQ(palette_rgb(PaletteColour::Black), (std::array<unsigned char, 3>{0x2e, 0x34, 0x36}));
  EXPECT_EQ(palette_rgb(PaletteColour::White), (std::array<unsigned char, 3>{0xee, 0xee, 0xec}));
  for (const auto colour : kPalette) {
    EXPECT_EQ(palette_from_name(palette_name(colour)), colour);
    EXPECT_NE(std::string(palette_names()).find(palette_name(colour)), std::string::npos);
  }
}

TEST(Canvas, StrokeAtMetresPaintsTheMatchingPixel) {
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::FreeplayMap);
  canvas.begin_stroke(1, PaletteColour::Purple, {0.3, -0.1});
  canvas.end_stroke(1);
  EXPECT_EQ(canvas.image().at<cv::Vec3b>(320, 960), bgr(PaletteColour::Purple));
  EXPECT_EQ(canvas.image().size(), cv::Size(1920, 1072));
}

TEST(Canvas, StrokeWidthIs50PxAt1920AndScalesWithTheRaster) {
  DrawingCanvas full(1920);
  full.begin_stroke(1, PaletteColour::Red, {0.3, -0.1});
  EXPECT_EQ(full.stroke_width_px(), 50);
  EXPECT_EQ(full.image().at<cv::Vec3b>(320, 960 + 23), bgr(PaletteColour::Red));
  EXPECT_EQ(full.image().at<cv::Vec3b>(320, 960 + 28), cv::Vec3b(0, 0, 0));
  DrawingCanvas half(960);
  half.begin_stroke(1, PaletteColour::Red, {0.3, -0.1});
  EXPECT_EQ(half.stroke_width_px(), 25);
  EXPECT_EQ(half.image().at<cv::Vec3b>(160, 480), bgr(PaletteColour::Red));
  EXPECT_EQ(half.image().at<cv::Vec3b>(160, 480 + 11), bgr(PaletteColour::Red));
  EXPECT_EQ(half.image().at<cv::Vec3b>(160, 480 + 15), cv::Vec3b(0, 0, 0));
}

TEST(Canvas, StrokesFollowTheFingerThroughMidpoints) {
  DrawingCanvas canvas(1920);
  canvas.begin_stroke(3, PaletteColour::Yellow, {0.1, -0.1});
  canvas.extend_stroke(3, {0.2, -0.1});
  canvas.extend_stroke(3, {0.2, -0.2});
  canvas.end_stroke(3);
  const auto at = [&](double x, double y) {
    const cv::Point2d p = canvas.to_pixel({x, y});
    return canvas.image().at<cv::Vec3b>(static_cast<int>(p.y), static_cast<int>(p.x));
  };
  EXPECT_EQ(at(0.15, -0.1), bgr(PaletteColour::Yellow));  // first midpoint
  EXPECT_EQ(at(0.2, -0.15), bgr(PaletteColour::Yellow));  // second midpoint
  EXPECT_EQ(at(0.2, -0.2), bgr(PaletteColour::Yellow));   // last point (end of stroke)
  EXPECT_EQ(at(0.1, -0.2), cv::Vec3b(0, 0, 0));           // far from the path
  // The corner at (0.2, −0.1) is smoothed: the curve passes inside it, not through it.
  EXPECT_EQ(at(0.2 + 0.0075, -0.1 + 0.0075), cv::Vec3b(0, 0, 0));
}

TEST(Canvas, EraserRestoresTheBackground) {
  DrawingCanvas canvas(1920);
  canvas.set_background(BackgroundKind::FreeplayMap);
  const cv::Mat bare = canvas.image().clone();
  canvas.begin_stroke(1, PaletteColour::Black, {0.3, -0.2});
  canvas.extend_stroke(1, {0.35, -0.2});
  canvas.end_stroke(1);
  const double painted = canvas.coverage();
  EXPECT_GT(painted, 0.0);
  const cv::Point2d centre = canvas.to_pixel({0.325, -0.2});
  EXPECT_EQ(canvas.image().at<cv::Vec3b>(static_cast<int>(centre.y), static_cast<int>(centre.x)),
            bgr(PaletteColour::Black));
  canvas.begin_stroke(2, PaletteColour::Eraser, {0.3, -0.2});
  canvas.extend_stroke(2, {0.35, -0.2});
  canvas.end_stroke(2);
  EXPECT_EQ(canvas.image().at<cv::Vec3b>(static_cast<int>(centre.y), static_cast<int>(centre.x)),
            bare.at<cv::Vec3b>(static_cast<int>(centre.y), static_cast<int>(centre.x)));
  EXPECT_LT(canvas.coverage(), 0.05 * painted);  // only the anti-aliased fringe may remain
}

TEST(Canvas, ClearAndBackgroundChangeRemoveStrokes) {
  DrawingCanvas canvas(640);
  canvas.set_background(BackgroundKind::Tutorial);
  const std::uint64_t bare = canvas.hash();
  canvas.begin_stroke(1, PaletteColour::Green, {0.3, -0.2});
  canvas.end_stroke(1);
  EXPECT_NE(canvas.hash(), bare);
  canvas.clear_strokes();
  EXPECT_EQ(canvas.hash(), bare);
  EXPECT_EQ(canvas.coverage(), 0.0);
  canvas.begin_stroke(1, PaletteColour::Green, {0.3, -0.2});
  canvas.set_background(BackgroundKind::FreeplayMap);
  EXPECT_EQ(canvas.coverage(), 0.0);
  EXPECT_EQ(canvas.active_strokes(), 0u);
  EXPECT_EQ(canvas.background_kind(), BackgroundKind::FreeplayMap);
}

TEST(Canvas, DirtyFlagTracksChanges) {
  DrawingCanvas canvas(320);
  EXPECT_TRUE(canvas.dirty());
  canvas.mark_published();
  EXPECT_FALSE(canvas.dirty());
  canvas.begin_stroke(1, PaletteColour::Blue, {0.1, -0.1});
  EXPECT_TRUE(canvas.dirty());
  canvas.mark_published();
  canvas.clear_strokes();
  EXPECT_TRUE(canvas.dirty());
}

TEST(Canvas, CoverageOfADotIsItsArea) {
  DrawingCanvas canvas(1920);
  canvas.begin_stroke(1, PaletteColour::White, {0.3, -0.17});
  canvas.end_stroke(1);
  const double pixels = 1920.0 * 1072.0;
  EXPECT_GT(canvas.coverage(), std::numbers::pi * 24.5 * 24.5 / pixels);  // 50 px wide …
  EXPECT_LT(canvas.coverage(), std::numbers::pi * 27.0 * 27.0 / pixels);  // … plus the anti-aliased fringe
}

TEST(Canvas, SameDrawingSameHash) {
  DrawingCanvas a(800), b(800);
  for (DrawingCanvas* c : {&a, &b}) {
    c->set_background(BackgroundKind::FreeplayMap);
    c->begin_stroke(4, PaletteColour::Orange, {0.1, -0.1});
    c->extend_stroke(4, {0.2, -0.15});
    c->end_stroke(4);
  }
  EXPECT_EQ(a.hash(), b.hash());
  b.begin_stroke(1, PaletteColour::Orange, {0.5, -0.3});
  EXPECT_NE(a.hash(), b.hash());
}

TEST(Canvas, SixSimultaneousStrokesAndNoMore) {
  DrawingCanvas canvas(640);
  for (int id = 1; id <= 6; ++id) canvas.begin_stroke(id, PaletteColour::Red, {0.05 * id, -0.1});
  for (int id = 1; id <= 6; ++id) canvas.extend_stroke(id, {0.05 * id, -0.2});
  EXPECT_EQ(canvas.active_strokes(), 6u);
  const std::uint64_t before = canvas.hash();
  EXPECT_THROW(canvas.begin_stroke(7, PaletteColour::Red, {0.5, -0.1}), InputError);
  EXPECT_EQ(canvas.hash(), before);
  EXPECT_EQ(canvas.active_strokes(), 6u);
  canvas.end_stroke(1);
  EXPECT_NO_THROW(canvas.begin_stroke(7, PaletteColour::Red, {0.5, -0.1}));
}

TEST(Canvas, BadStrokeInputIsRejected) {
  DrawingCanvas canvas(640);
  EXPECT_THROW(canvas.extend_stroke(2, {0.1, -0.1}), InputError);
  EXPECT_THROW(canvas.begin_stroke(1, PaletteColour::Red, {std::nan(""), -0.1}), InputError);
  EXPECT_EQ(canvas.active_strokes(), 0u);
  EXPECT_NO_THROW(canvas.end_stroke(42));  // lifting an unknown finger is harmless
  EXPECT_THROW(DrawingCanvas bad(0), InputError);
}

TEST(Canvas, StrokesOffTheScreenAreClipped) {
  DrawingCanvas canvas(640);
  canvas.begin_stroke(1, PaletteColour::Red, {-1.0, 1.0});
  canvas.extend_stroke(1, {-2.0, 2.0});
  canvas.end_stroke(1);
  EXPECT_EQ(canvas.coverage(), 0.0);
  canvas.begin_stroke(1, PaletteColour::Red, {0.0, 0.0});  // the corner: a quarter dot
  EXPECT_GT(canvas.coverage(), 0.0);
}

}  // namespace
}  // namespace freeplay::sim
