// Raster speed: zone segmentation per background update, screen image, background rasterisation, strokes.

#include <benchmark/benchmark.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "freeplay/sim/background.hpp"
#include "freeplay/sim/canvas.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/screen_renderer.hpp"
#include "freeplay/sim/zone_raster.hpp"
#include "freeplay/sim/zones.hpp"

namespace freeplay::sim {
namespace {

/// Zone segmentation of the 1920-wide map with a drawing on it (what each background republication costs).
void BM_ZoneSegmentation(benchmark::State& state) {
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::FreeplayMap);
  canvas.begin_stroke(1, PaletteColour::Blue, {0.35, -0.25});
  canvas.extend_stroke(1, {0.42, -0.28});
  canvas.end_stroke(1);
  std::size_t zones = 0;
  for (auto _ : state) {
    const ZoneMap map = ZoneMap::segment(canvas.image(), kMetresPerPixel);
    zones = map.zones().size();
    benchmark::DoNotOptimize(zones);
  }
  state.counters["zones"] = static_cast<double>(zones);
}
BENCHMARK(BM_ZoneSegmentation)->Unit(benchmark::kMillisecond);

/// What a background publication costs in an episode (960 px raster): one short stroke since the last
/// publication, then the incremental segmentation (only the colour masks the stroke changed are redone).
void BM_ZoneSegmentationAfterStroke(benchmark::State& state) {
  DrawingCanvas canvas(960);
  canvas.set_background(BackgroundKind::FreeplayMap);
  const double scale = kScreenWidthM / canvas.width_px();
  ZoneSegmenter segmenter;
  segmenter.segment(canvas.image(), scale);
  int k = 0;
  for (auto _ : state) {
    const Vec2 at(0.05 + 0.5 * ((k * 37) % 100) / 100.0, -0.05 - 0.25 * ((k * 61) % 100) / 100.0);
    canvas.begin_stroke(1, k % 2 == 0 ? PaletteColour::Blue : PaletteColour::Red, at);
    canvas.extend_stroke(1, at + Vec2(0.02, -0.01));
    canvas.end_stroke(1);
    ++k;
    const ZoneMap map = segmenter.segment(canvas.image(), scale);
    benchmark::DoNotOptimize(map.zones().size());
  }
  const auto& counters = segmenter.counters();
  state.counters["masks_redone_share"] =
      static_cast<double>(counters.masks_recomputed) / static_cast<double>(counters.masks_recomputed + counters.masks_reused);
}
BENCHMARK(BM_ZoneSegmentationAfterStroke)->Unit(benchmark::kMicrosecond);

/// One 10 Hz stroke extension on the 960 px raster (a child drawing: smoothing + anti-aliased 25 px line).
void BM_StrokeExtension(benchmark::State& state) {
  DrawingCanvas canvas(960);
  canvas.set_background(BackgroundKind::FreeplayMap);
  canvas.begin_stroke(1, PaletteColour::Green, {0.1, -0.1});
  int k = 0;
  for (auto _ : state) {
    const double phase = 0.05 * k++;
    canvas.extend_stroke(1, {0.3 + 0.2 * std::sin(phase), -0.17 + 0.12 * std::cos(1.3 * phase)});
  }
  canvas.end_stroke(1);
}
BENCHMARK(BM_StrokeExtension)->Unit(benchmark::kMicrosecond);

/// The full screen image (map + strokes, stash, palette, all 10 items rotated, touches, robot hand).
void BM_ScreenImage(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0));
  const ItemCatalogue catalogue = ItemCatalogue::load_default();
  const ScreenRenderer renderer(catalogue);
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::FreeplayMap);
  std::vector<ItemView> items;
  int z = 0;
  for (const ItemSpec& spec : catalogue.items()) {
    items.push_back({&spec, {0.05 + 0.05 * z, -0.1 - 0.015 * (z % 4), 0.37 * z}, z, true});
    ++z;
  }
  ScreenOverlay overlay;
  overlay.touches = {{0.1, -0.3}, {0.2, -0.25}};
  overlay.robot_hand = Vec2(0.4, -0.2);
  overlay.palette_visible = true;
  renderer.render(canvas.image(), items, overlay, width);  // fills the picture cache
  for (auto _ : state) {
    cv::Mat screen = renderer.render(canvas.image(), items, overlay, width);
    benchmark::DoNotOptimize(screen.data);
  }
}
BENCHMARK(BM_ScreenImage)->Arg(1920)->Arg(960)->Unit(benchmark::kMillisecond);

/// Rasterising the map description (each StartFreeplay / StartItemsPlacement).
void BM_RenderMap(benchmark::State& state) {
  for (auto _ : state) {
    cv::Mat map = render_background(BackgroundKind::FreeplayMap, kScreenWidthPx);
    benchmark::DoNotOptimize(map.data);
  }
}
BENCHMARK(BM_RenderMap)->Unit(benchmark::kMillisecond);

/// One finger move while drawing (a quadratic segment of a 50 px stroke at 1920 px).
void BM_StrokeSegment(benchmark::State& state) {
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::FreeplayMap);
  canvas.begin_stroke(1, PaletteColour::Red, {0.1, -0.1});
  double x = 0.1;
  for (auto _ : state) {
    x = x > 0.5 ? 0.1 : x + 0.005;
    canvas.extend_stroke(1, {x, -0.1 - 0.05 * (x - 0.1)});
  }
}
BENCHMARK(BM_StrokeSegment)->Unit(benchmark::kMicrosecond);

/// Canvas hash and coverage after a change (state hashing, statistics).
void BM_CanvasHash(benchmark::State& state) {
  DrawingCanvas canvas(kScreenWidthPx);
  canvas.set_background(BackgroundKind::FreeplayMap);
  canvas.begin_stroke(1, PaletteColour::Red, {0.1, -0.1});
  double x = 0.1;
  for (auto _ : state) {
    x = x > 0.5 ? 0.1 : x + 0.005;
    canvas.extend_stroke(1, {x, -0.1});
    benchmark::DoNotOptimize(canvas.hash());
  }
}
BENCHMARK(BM_CanvasHash)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace freeplay::sim

namespace freeplay::sim {
namespace {

/// One colour's windowed raster update after a small blob changed in its 200 px mask (a stroke's footprint): the
/// opening, distance transform and threshold around it, and the contour search when the foreground moved.
void BM_ColourRasterWindowedUpdate(benchmark::State& state) {
  DrawingCanvas canvas(960);
  canvas.set_background(BackgroundKind::FreeplayMap);
  cv::Mat hsv;
  cv::Mat small;
  cv::cvtColor(canvas.image(), hsv, cv::COLOR_BGR2HSV);
  cv::resize(hsv, small, cv::Size(kZoneSegmentationWidthPx, 112));
  const HsvRange range = zone_hsv_range("green");
  detail::ColourRaster raster;
  raster.resize(small.size());
  cv::inRange(small, cv::Scalar(range.lower[0], range.lower[1], range.lower[2]),
              cv::Scalar(range.upper[0], range.upper[1], range.upper[2]), raster.mask());
  ZoneSegmenterCounters work;
  raster.update(cv::Rect(0, 0, small.cols, small.rows), work);
  int k = 0;
  for (auto _ : state) {
    const cv::Point at(10 + (k * 37) % 180, 10 + (k * 61) % 92);
    const cv::Rect blob(at.x - 4, at.y - 3, 9, 7);
    cv::rectangle(raster.mask(), blob, cv::Scalar(k % 2 == 0 ? 0 : 255), cv::FILLED);
    raster.update(blob, work);
    benchmark::DoNotOptimize(raster.contours().size());
    ++k;
  }
  state.counters["contour_search_share"] = static_cast<double>(work.contour_searches) / static_cast<double>(k);
  state.counters["distance_px_per_update"] = static_cast<double>(work.distance_pixels) / static_cast<double>(k);
}
BENCHMARK(BM_ColourRasterWindowedUpdate)->Unit(benchmark::kMicrosecond);

/// The same colour's whole-image pipeline with the real node's OpenCV calls (what each update cost before).
void BM_ColourRasterReference(benchmark::State& state) {
  DrawingCanvas canvas(960);
  canvas.set_background(BackgroundKind::FreeplayMap);
  cv::Mat hsv;
  cv::Mat small;
  cv::Mat mask;
  cv::cvtColor(canvas.image(), hsv, cv::COLOR_BGR2HSV);
  cv::resize(hsv, small, cv::Size(kZoneSegmentationWidthPx, 112));
  const HsvRange range = zone_hsv_range("green");
  cv::inRange(small, cv::Scalar(range.lower[0], range.lower[1], range.lower[2]),
              cv::Scalar(range.upper[0], range.upper[1], range.upper[2]), mask);
  for (auto _ : state) benchmark::DoNotOptimize(detail::reference_contours(mask).size());
}
BENCHMARK(BM_ColourRasterReference)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace freeplay::sim
