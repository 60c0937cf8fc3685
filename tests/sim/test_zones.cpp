// Zones: counts on our map (stable), queries, coordinate signs, drawing changes zones, bad input.

#include <gtest/gtest.h>

#include <tuple>

#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/canvas.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::sim {
namespace {

ZoneMap zones_of(const DrawingCanvas& canvas) {
  return ZoneMap::segment(canvas.image(), kScreenWidthM / canvas.width_px());
}

/// Fills a `side` × `side` square centred on `centre` with zig-zag strokes, as a child colouring in.
void scribble(DrawingCanvas& canvas, PaletteColour colour, const Vec2& centre, double side, int stroke_id = 1) {
  const double half = side / 2;
  canvas.begin_stroke(stroke_id, colour, centre + Vec2(-half, half));
  bool right = true;
  for (double y = half; y >= -half - 1e-9; y -= 0.01) {
    canvas.extend_stroke(stroke_id, centre + Vec2(right ? half : -half, y));
    canvas.extend_stroke(stroke_id, centre + Vec2(right ? half : -half, y - 0.005));
    right = !right;
  }
  canvas.end_stroke(stroke_id);
}

class MapZones : public ::testing::Test {
 protected:
  void SetUp() override { canvas_.set_background(BackgroundKind::FreeplayMap); }
  DrawingCanvas canvas_{kScreenWidthPx};
};

// Our map is designed to give the real-session counts (4 blue, 1 yellow, 5 black, 5 green, 1 white).
TEST_F(MapZones, CountsOnTheDefaultMapAreStable) {
  for (const int width : {kScreenWidthPx, 960, 1280}) {
    DrawingCanvas canvas(width);
    canvas.set_background(BackgroundKind::FreeplayMap);
    const ZoneMap zones = zones_of(canvas);
    SCOPED_TRACE(width);
    EXPECT_EQ(zones.count("green"), 5u);
    EXPECT_EQ(zones.count("blue"), 4u);
    EXPECT_EQ(zones.count("yellow"), 1u);
    EXPECT_EQ(zones.count("white"), 1u);
    EXPECT_EQ(zones.count("black"), 5u);
    EXPECT_EQ(zones.count("purple"), 0u);
    EXPECT_EQ(zones.count("red"), 0u);
    EXPECT_EQ(zones.zones().size(), 16u);
  }
}

TEST_F(MapZones, KnownPlacesHaveTheirColour) {
  const ZoneMap zones = zones_of(canvas_);
  const auto colour_at = [&](const Vec2& p) {
    const Zone* zone = zones.at(p);
    return zone ? zone->colour : std::string("none");
  };
  EXPECT_EQ(colour_at({0.08, -0.30}), "blue");    // lake
  EXPECT_EQ(colour_at({0.09, -0.06}), "white");   // castle courtyard
  EXPECT_EQ(colour_at({0.37, -0.28}), "green");   // grass
  EXPECT_EQ(colour_at({0.56, -0.03}), "yellow");  // savanna
  EXPECT_EQ(colour_at({0.017, -0.113}), "black"); // a tower
  EXPECT_EQ(colour_at({0.3, 0.05}), "none");      // off the screen
}

TEST_F(MapZones, PolygonsAreInTheSandtrayFrame) {
  const ZoneMap zones = zones_of(canvas_);
  for (const Zone& zone : zones.zones()) {
    ASSERT_GE(zone.polygon.size(), 3u) << zone.colour << zone.id;
    for (const Vec2& p : zone.polygon) {
      EXPECT_GE(p.x(), 0.0);
      EXPECT_LE(p.x(), kScreenWidthM);
      EXPECT_LE(p.y(), 0.0);
      EXPECT_GE(p.y(), -kScreenHeightM);
    }
    EXPECT_TRUE(zone.centroid.isApprox(vertex_mean(zone.polygon)));
    EXPECT_GT(zone.area_m2, 0.0);
  }
}

TEST_F(MapZones, IdsCountUpPerColour) {
  const ZoneMap zones = zones_of(canvas_);
  for (const auto colour : kZoneColours) {
    int expected = 0;
    for (const Zone* zone : zones.of_colour(colour)) EXPECT_EQ(zone->id, expected++);
  }
}

TEST_F(MapZones, ABlueDrawingOnGrassMakesANewBlueZone) {
  const std::size_t before = zones_of(canvas_).count("blue");
  const Vec2 centre(0.37, -0.28);
  scribble(canvas_, PaletteColour::Blue, centre, 0.06);
  const ZoneMap after = zones_of(canvas_);
  EXPECT_EQ(after.count("blue"), before + 1);
  const Zone* zone = after.at(centre);
  ASSERT_NE(zone, nullptr);
  EXPECT_EQ(zone->colour, "blue");
  EXPECT_LT((zone->centroid - centre).norm(), 0.01);
  // RETR_TREE: the grass around the drawing stays one zone and gains a hole contour, published as a zone too.
  EXPECT_EQ(after.count("green"), 6u);
}

TEST_F(MapZones, ErasingTheDrawingRestoresTheZones) {
  const ZoneMap bare = zones_of(canvas_);
  scribble(canvas_, PaletteColour::Purple, {0.37, -0.28}, 0.06);
  EXPECT_EQ(zones_of(canvas_).count("purple"), 1u);
  scribble(canvas_, PaletteColour::Eraser, {0.37, -0.28}, 0.08, 2);
  const ZoneMap erased = zones_of(canvas_);
  for (const auto colour : kZoneColours) EXPECT_EQ(erased.count(colour), bare.count(colour)) << colour;
}

TEST(Zones, TutorialIsOneWhiteZone) {
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::Tutorial);
  const ZoneMap zones = zones_of(canvas);
  EXPECT_EQ(zones.count("white"), 1u);
  EXPECT_EQ(zones.zones().size(), 1u);  // the thin ring outlines do not survive the opening
  ASSERT_NE(zones.at({0.3, -0.17}), nullptr);
  EXPECT_EQ(zones.at({0.3, -0.17})->colour, "white");
}

TEST(Zones, BlankScreenIsOneBlackZone) {
  DrawingCanvas canvas(640);
  const ZoneMap zones = zones_of(canvas);
  EXPECT_EQ(zones.count("black"), 1u);
  EXPECT_EQ(zones.zones().size(), 1u);
}

TEST(Zones, NestedZonesAnswerTheSmallest) {
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::Tutorial);
  scribble(canvas, PaletteColour::Red, {0.45, -0.17}, 0.06);
  const ZoneMap zones = zones_of(canvas);
  ASSERT_NE(zones.at({0.45, -0.17}), nullptr);
  EXPECT_EQ(zones.at({0.45, -0.17})->colour, "red");
  EXPECT_EQ(zones.at({0.1, -0.3})->colour, "white");
}

TEST(Zones, SegmentationIsDeterministic) {
  DrawingCanvas canvas(960);
  canvas.set_background(BackgroundKind::FreeplayMap);
  const ZoneMap a = zones_of(canvas), b = zones_of(canvas);
  ASSERT_EQ(a.zones().size(), b.zones().size());
  for (std::size_t i = 0; i < a.zones().size(); ++i) EXPECT_EQ(a.zones()[i].polygon, b.zones()[i].polygon);
}

TEST(Zones, BadInputIsAnInputError) {
  EXPECT_THROW(ZoneMap::segment(cv::Mat(), kMetresPerPixel), InputError);
  EXPECT_THROW(ZoneMap::segment(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0)), kMetresPerPixel), InputError);
  EXPECT_THROW(ZoneMap::segment(cv::Mat(100, 100, CV_8UC3, cv::Scalar(0)), 0.0), InputError);
  const ZoneMap empty;
  EXPECT_EQ(empty.at({0.1, -0.1}), nullptr);
  try {
    empty.count("pink");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.allowed(), "green, blue, yellow, white, black, purple, red");
  }
  EXPECT_THROW(empty.of_colour("orange"), InputError);
}

TEST(Zones, RangesAndMarkerColoursAreTheRealOnes) {
  EXPECT_EQ(zone_hsv_range("blue").lower, (std::array<int, 3>{70, 0, 70}));
  EXPECT_EQ(zone_hsv_range("yellow").upper, (std::array<int, 3>{40, 255, 255}));
  const auto blue = zone_marker_rgb("blue");
  EXPECT_GT(blue[2], blue[0]);
  EXPECT_GT(blue[2], blue[1]);
  const auto red = zone_marker_rgb("red");
  EXPECT_GT(red[0], red[1]);
}

}  // namespace
}  // namespace freeplay::sim

namespace freeplay::sim {
namespace {

// The segmentation converts only the rows the bilinear downsampling reads; it must equal the plain pipeline.
TEST(Zones, RowSkippingEqualsTheFullResolutionPipeline) {
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::FreeplayMap);
  canvas.begin_stroke(1, PaletteColour::Red, {0.31, -0.21});
  canvas.extend_stroke(1, {0.36, -0.23});
  canvas.extend_stroke(1, {0.40, -0.19});
  canvas.end_stroke(1);
  for (const int width : {kScreenWidthPx, 1000, 777}) {
    cv::Mat image;
    cv::resize(canvas.image(), image, cv::Size(width, raster_height(width)), 0, 0, cv::INTER_AREA);
    // The real node, step by step.
    cv::Mat hsv, small;
    cv::cvtColor(image, hsv, cv::COLOR_BGR2HSV);
    const int small_height = static_cast<int>(std::lround(image.rows * 200.0 / image.cols));
    cv::resize(hsv, small, cv::Size(200, small_height));
    const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
    std::vector<Polygon2> expected;
    for (const auto colour : kZoneColours) {
      const HsvRange r = zone_hsv_range(colour);
      cv::Mat mask, distance, foreground;
      cv::inRange(small, cv::Scalar(r.lower[0], r.lower[1], r.lower[2]), cv::Scalar(r.upper[0], r.upper[1], r.upper[2]),
                  mask);
      cv::morphologyEx(mask, mask, cv::MORPH_OPEN, kernel, cv::Point(-1, -1), 2);
      cv::dilate(mask, mask, kernel);
      cv::distanceTransform(mask, distance, cv::DIST_L2, cv::DIST_MASK_5);
      double max_distance = 0;
      cv::minMaxLoc(distance, nullptr, &max_distance);
      cv::threshold(distance, foreground, 0.25 * max_distance, 255, cv::THRESH_BINARY);
      foreground.convertTo(foreground, CV_8U);
      cv::dilate(foreground, foreground, kernel, cv::Point(-1, -1), 2);
      std::vector<std::vector<cv::Point>> contours;
      cv::findContours(foreground, contours, cv::RETR_TREE, cv::CHAIN_APPROX_TC89_KCOS);
      const double mpp = kScreenWidthM / width;
      for (const auto& contour : contours) {
        Polygon2 polygon;
        for (const auto& p : contour) {
          polygon.emplace_back(p.x * (width / 200.0) * mpp, -p.y * (static_cast<double>(image.rows) / small_height) * mpp);
        }
        expected.push_back(polygon);
      }
    }
    const ZoneMap zones = ZoneMap::segment(image, kScreenWidthM / width);
    ASSERT_EQ(zones.zones().size(), expected.size()) << width;
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(zones.zones()[i].polygon, expected[i]) << width;
  }
}

}  // namespace
}  // namespace freeplay::sim

namespace freeplay::sim {
namespace {

bool same_zones(const ZoneMap& a, const ZoneMap& b) {
  if (a.zones().size() != b.zones().size()) return false;
  for (std::size_t i = 0; i < a.zones().size(); ++i) {
    const auto& x = a.zones()[i];
    const auto& y = b.zones()[i];
    if (x.colour != y.colour || x.id != y.id || x.polygon != y.polygon || x.area_m2 != y.area_m2) return false;
  }
  return true;
}

// The incremental segmenter reuses unchanged colour masks and still gives exactly the from-scratch zones.
TEST(ZoneSegmenter, ReusesUnchangedMasksAndMatchesAFullSegmentation) {
  DrawingCanvas canvas(960);
  canvas.set_background(BackgroundKind::FreeplayMap);
  const double scale = kScreenWidthM / canvas.width_px();
  ZoneSegmenter segmenter;
  EXPECT_TRUE(same_zones(segmenter.segment(canvas.image(), scale), ZoneMap::segment(canvas.image(), scale)));
  const auto first = segmenter.counters();
  EXPECT_EQ(first.masks_recomputed + first.masks_reused, kZoneColours.size());
  // The same image again: nothing is recomputed.
  EXPECT_TRUE(same_zones(segmenter.segment(canvas.image(), scale), ZoneMap::segment(canvas.image(), scale)));
  EXPECT_EQ(segmenter.counters().masks_recomputed, first.masks_recomputed);
  EXPECT_EQ(segmenter.counters().masks_reused, first.masks_reused + kZoneColours.size());
  // A second segmenter on this thread finds every mask in the memo.
  ZoneSegmenter again;
  EXPECT_TRUE(same_zones(again.segment(canvas.image(), scale), ZoneMap::segment(canvas.image(), scale)));
  EXPECT_EQ(again.counters().masks_recomputed, 0u);
  // Red strokes: the red mask (and the masks of what they cover) change, the others are reused.
  for (int k = 0; k < 4; ++k) {
    scribble(canvas, k % 2 == 0 ? PaletteColour::Red : PaletteColour::Blue, Vec2(0.1 + 0.1 * k, -0.15), 0.06);
    EXPECT_TRUE(same_zones(segmenter.segment(canvas.image(), scale), ZoneMap::segment(canvas.image(), scale)))
        << "after stroke " << k;
  }
  EXPECT_EQ(segmenter.counters().images, 6u);
  EXPECT_GT(segmenter.counters().masks_reused, kZoneColours.size());
  EXPECT_LT(segmenter.counters().masks_recomputed, 6 * kZoneColours.size());
}

// Told which pixels changed (a rectangle, or row by row as the sandtray tells it), the segmenter converts and
// compares only those, and still gives exactly the from-scratch zones: small strokes in different places one after
// the other, no change, and long diagonal strokes.
TEST(ZoneSegmenter, ChangedRectanglesGiveTheFromScratchZones) {
  for (const bool row_by_row : {false, true}) {
    DrawingCanvas canvas(960);
    canvas.set_background(BackgroundKind::FreeplayMap);
    const double scale = kScreenWidthM / canvas.width_px();
    ZoneSegmenter segmenter;
    const auto segment_changes = [&] {
      const auto zones = row_by_row ? segmenter.segment(canvas.image(), scale, canvas.unpublished())
                                    : segmenter.segment(canvas.image(), scale, canvas.unpublished_rect());
      canvas.mark_published();
      return zones;
    };
    EXPECT_TRUE(same_zones(segment_changes(), ZoneMap::segment(canvas.image(), scale)));
    const std::array<Vec2, 5> centres = {Vec2(0.1, -0.05), Vec2(0.45, -0.28), Vec2(0.3, -0.15), Vec2(0.3, -0.15),
                                         Vec2(0.12, -0.3)};
    for (std::size_t k = 0; k < centres.size(); ++k) {
      scribble(canvas, k % 2 == 0 ? PaletteColour::Red : PaletteColour::Yellow, centres[k], 0.04);
      EXPECT_TRUE(same_zones(segment_changes(), ZoneMap::segment(canvas.image(), scale))) << "after stroke " << k;
      EXPECT_TRUE(same_zones(segment_changes(), ZoneMap::segment(canvas.image(), scale))) << "no change after " << k;
    }
    // Back to the bare background: the pixels the strokes changed change back.
    scribble(canvas, PaletteColour::Blue, Vec2(0.2, -0.2), 0.04);
    EXPECT_TRUE(same_zones(segment_changes(), ZoneMap::segment(canvas.image(), scale)));
    canvas.clear_strokes();
    EXPECT_TRUE(same_zones(segment_changes(), ZoneMap::segment(canvas.image(), scale)));
    // Two strokes far apart before one publication: rows between them change nowhere.
    scribble(canvas, PaletteColour::Purple, Vec2(0.5, -0.05), 0.03);
    scribble(canvas, PaletteColour::Red, Vec2(0.1, -0.3), 0.03);
    EXPECT_TRUE(same_zones(segment_changes(), ZoneMap::segment(canvas.image(), scale)));
    // A long diagonal stroke: its rows' columns are a small part of its box.
    for (int k = 0; k < 3; ++k) {
      canvas.begin_stroke(1, PaletteColour::Green, Vec2(0.05 + 0.1 * k, -0.03));
      for (int step = 1; step <= 20; ++step) {
        canvas.extend_stroke(1, Vec2(0.05 + 0.1 * k + 0.012 * step, -0.03 - 0.013 * step));
      }
      canvas.end_stroke(1);
      EXPECT_TRUE(same_zones(segment_changes(), ZoneMap::segment(canvas.image(), scale))) << "diagonal " << k;
    }
  }
}

// A background this thread converted before is recalled, not converted again, and a segmenter that recalled it copies
// it before its first stroke is converted: strokes on one segmenter never reach what another recalls.
TEST(ZoneSegmenter, RecalledBackgroundsGiveTheFromScratchZones) {
  const double scale = kScreenWidthM / 960;
  DrawingCanvas first_canvas(960);
  DrawingCanvas second_canvas(960);
  ZoneSegmenter first;
  ZoneSegmenter second;
  const auto segment_changes = [scale](ZoneSegmenter& segmenter, DrawingCanvas& canvas) {
    const auto zones = segmenter.segment(canvas.image(), scale, canvas.unpublished_rect());
    canvas.mark_published();
    EXPECT_TRUE(same_zones(zones, ZoneMap::segment(canvas.image(), scale)));
  };
  first_canvas.set_background(BackgroundKind::Tutorial);
  segment_changes(first, first_canvas);
  for (int round = 0; round < 2; ++round) {
    for (auto* canvas : {&first_canvas, &second_canvas}) canvas->set_background(BackgroundKind::FreeplayMap);
    segment_changes(first, first_canvas);
    scribble(first_canvas, PaletteColour::Red, Vec2(0.2 + 0.1 * round, -0.15), 0.05);
    segment_changes(first, first_canvas);
    segment_changes(second, second_canvas);
    scribble(second_canvas, PaletteColour::Yellow, Vec2(0.35, -0.2 + 0.05 * round), 0.05);
    segment_changes(second, second_canvas);
  }
  // The map was converted at most once on this thread (by `first` in round 0, unless an earlier test did): recalled
  // at least three times since.
  EXPECT_GE(first.counters().images_recalled + second.counters().images_recalled, 3u);
}

// The episode raster (960 × 536 → 200 × 112) downsamples in bands of 14 rows and tiles of 5 columns; any run of tiles
// in a band then resizes alone exactly as the whole image does. Sizes without common divisors resize whole.
TEST(ZoneSegmenter, ResizeTilesResizeAloneExactly) {
  const detail::ResizeTiles tiles = detail::resize_tiles({960, 536}, {200, 112});
  EXPECT_EQ(tiles.band_rows, 14);
  EXPECT_EQ(tiles.tile_cols, 5);
  cv::Mat image(536, 960, CV_8UC3);
  cv::RNG rng(5);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  cv::Mat whole;
  cv::resize(image, whole, {200, 112}, 0, 0, cv::INTER_LINEAR);
  for (const auto& [band, first, count] : {std::tuple{0, 0, 40}, {3, 17, 1}, {7, 29, 11}, {5, 39, 1}, {2, 3, 6}}) {
    cv::Mat block;
    cv::resize(image(cv::Rect(first * 24, band * 67, count * 24, 67)), block, {count * 5, 14}, 0, 0, cv::INTER_LINEAR);
    EXPECT_EQ(cv::norm(whole(cv::Rect(first * 5, band * 14, count * 5, 14)), block, cv::NORM_INF), 0.0)
        << "band " << band << ", tiles " << first << "+" << count;
  }
  const detail::ResizeTiles prime = detail::resize_tiles({961, 537}, {200, 112});
  EXPECT_EQ(prime.band_rows, 112);
  EXPECT_EQ(prime.tile_cols, 200);
}

}  // namespace
}  // namespace freeplay::sim
