// The screen image: background + strokes, stash strip, palette, items in z order, touches and the robot finger.

#include "freeplay/sim/screen_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <string>

#include <opencv2/imgproc.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/background.hpp"

namespace freeplay::sim {
namespace {

constexpr int kMinWidthPx = 16;
constexpr int kMaxWidthPx = 16384;
constexpr int kStashBorderPx = 5;       // lighter left border of the stash (at 1920 px)
constexpr int kSwatchPx = 60;           // palette swatch side (at 1920 px)
constexpr int kEraserPx = 80;           // eraser button side (at 1920 px)
constexpr double kTouchRadiusM = 0.004; // drawn finger dot
constexpr double kRobotRadiusM = 0.007; // drawn robot-finger marker

cv::Scalar bgr_of(PaletteColour colour) {
  const auto rgb = palette_rgb(colour);
  return {static_cast<double>(rgb[2]), static_cast<double>(rgb[1]), static_cast<double>(rgb[0])};
}

int scaled(int px_at_1920, int width_px) {
  return std::max(1, static_cast<int>(std::lround(px_at_1920 * width_px / static_cast<double>(kScreenWidthPx))));
}

/// Alpha-blends the BGRA `layer` onto the BGR `target` with the layer's top-left corner at `origin` (clipped).
void blend(cv::Mat& target, const cv::Mat& layer, cv::Point origin) {
  const cv::Rect placed(origin, layer.size());
  const cv::Rect visible = placed & cv::Rect(0, 0, target.cols, target.rows);
  if (visible.empty()) return;
  for (int row = 0; row < visible.height; ++row) {
    const auto* src = layer.ptr<cv::Vec4b>(visible.y - placed.y + row) + (visible.x - placed.x);
    auto* dst = target.ptr<cv::Vec3b>(visible.y + row) + visible.x;
    for (int col = 0; col < visible.width; ++col) {
      const unsigned a = src[col][3];
      if (a == 0) continue;
      if (a == 255) {
        dst[col] = {src[col][0], src[col][1], src[col][2]};
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        dst[col][c] = static_cast<unsigned char>((src[col][c] * a + dst[col][c] * (255u - a) + 127u) / 255u);
      }
    }
  }
}

void draw_palette(cv::Mat& screen) {
  const int width = screen.cols;
  const int swatch = scaled(kSwatchPx, width);
  const int eraser = scaled(kEraserPx, width);
  const int rows = 4;
  const int total_height = rows * swatch + eraser;
  const int top = (screen.rows - total_height) / 2;
  const cv::Scalar frame(40, 40, 40);
  for (int i = 0; i < 8; ++i) {
    const cv::Rect cell((i % 2) * swatch, top + (i / 2) * swatch, swatch, swatch);
    cv::rectangle(screen, cell, bgr_of(kPalette[static_cast<std::size_t>(i)]), cv::FILLED);
    cv::rectangle(screen, cell, frame, 1);
  }
  const cv::Rect button(0, top + rows * swatch, eraser, eraser);
  cv::rectangle(screen, button, cv::Scalar(220, 220, 220), cv::FILLED);
  cv::rectangle(screen, button, frame, 1);
  // A pink eraser block, drawn diagonally.
  const cv::Point2f centre(button.x + eraser / 2.0f, button.y + eraser / 2.0f);
  const cv::RotatedRect block(centre, cv::Size2f(eraser * 0.7f, eraser * 0.3f), -35.0f);
  cv::Point2f corners[4];
  block.points(corners);
  std::vector<cv::Point> poly(corners, corners + 4);
  cv::fillConvexPoly(screen, poly, cv::Scalar(180, 150, 240), cv::LINE_AA);
  cv::polylines(screen, std::vector<std::vector<cv::Point>>{poly}, true, frame, 1, cv::LINE_AA);
}

void check_width(int width_px) {
  if (width_px < kMinWidthPx || width_px > kMaxWidthPx) {
    throw InputError("screen width " + std::to_string(width_px) + " px is out of range", "width",
                     std::to_string(kMinWidthPx) + "…" + std::to_string(kMaxWidthPx) + " px");
  }
}

}  // namespace

struct ScreenRenderer::PictureCache {
  std::mutex mutex;
  std::map<std::pair<std::string, int>, cv::Mat> pictures;  // (item name, side px) → BGRA picture

  /// The picture of `spec` at `side_px`, drawn once per size.
  cv::Mat get(const ItemSpec& spec, int side_px) {
    const std::lock_guard lock(mutex);
    auto [it, inserted] = pictures.try_emplace({spec.name, side_px});
    if (inserted) it->second = item_picture(spec, side_px);
    return it->second;  // shares the pixels; they are never written after insertion
  }
};

ScreenRenderer::ScreenRenderer(const ItemCatalogue& catalogue)
    : catalogue_(catalogue), cache_(std::make_unique<PictureCache>()) {}

ScreenRenderer::~ScreenRenderer() = default;

cv::Mat ScreenRenderer::render(const cv::Mat& background, const std::vector<ItemView>& items,
                               const ScreenOverlay& overlay, int width_px) const {
  check_width(width_px);
  if (background.empty() || background.type() != CV_8UC3) {
    throw InputError("the background is empty or not 8-bit BGR", "background", "a BGR CV_8UC3 image");
  }
  const int height_px = raster_height(width_px);
  const double metres_per_pixel = kScreenWidthM / width_px;
  cv::Mat screen;
  if (background.cols == width_px && background.rows == height_px) {
    screen = background.clone();
  } else {
    cv::resize(background, screen, cv::Size(width_px, height_px), 0, 0,
               background.cols > width_px ? cv::INTER_AREA : cv::INTER_LINEAR);
  }

  if (overlay.stash_visible) {
    const int stash_x = static_cast<int>(std::lround(width_px * (1.0 - kStashFraction)));
    cv::rectangle(screen, cv::Rect(stash_x, 0, width_px - stash_x, height_px), cv::Scalar(0x11, 0x11, 0x11), cv::FILLED);
    cv::rectangle(screen, cv::Rect(stash_x, 0, scaled(kStashBorderPx, width_px), height_px),
                  cv::Scalar(0x44, 0x44, 0x44), cv::FILLED);
  }
  if (overlay.palette_visible) draw_palette(screen);

  std::vector<const ItemView*> order;
  for (const auto& item : items) {
    if (item.visible && item.spec != nullptr) order.push_back(&item);
  }
  std::stable_sort(order.begin(), order.end(), [](const ItemView* a, const ItemView* b) { return a->z < b->z; });
  for (const ItemView* item : order) {
    const int side = std::max(4, static_cast<int>(std::lround(item->spec->box_side_m / metres_per_pixel)));
    const cv::Mat picture = cache_->get(*item->spec, side);
    const double cx = item->pose.x / metres_per_pixel;
    const double cy = -item->pose.y / metres_per_pixel;
    if (!std::isfinite(cx) || !std::isfinite(cy) || !std::isfinite(item->pose.theta)) {
      throw InputError("item pose is not finite", item->spec->name, "finite x, y, theta");
    }
    // θ is counter-clockwise in `sandtray` (y up), which is counter-clockwise on the screen too: OpenCV's
    // positive angle. Warp only the item's bounding square.
    const double c = std::abs(std::cos(item->pose.theta)), s = std::abs(std::sin(item->pose.theta));
    const int bound = static_cast<int>(std::ceil(side * (c + s))) + 2;
    const cv::Point origin(static_cast<int>(std::floor(cx - bound / 2.0)), static_cast<int>(std::floor(cy - bound / 2.0)));
    if (!(cv::Rect(origin, cv::Size(bound, bound)) & cv::Rect(0, 0, width_px, height_px)).area()) continue;
    cv::Mat transform = cv::getRotationMatrix2D(cv::Point2f(side / 2.0f, side / 2.0f),
                                                item->pose.theta * 180.0 / std::numbers::pi, 1.0);
    transform.at<double>(0, 2) += (cx - origin.x) - side / 2.0;
    transform.at<double>(1, 2) += (cy - origin.y) - side / 2.0;
    cv::Mat warped;
    cv::warpAffine(picture, warped, transform, cv::Size(bound, bound), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                   cv::Scalar(0, 0, 0, 0));
    blend(screen, warped, origin);
  }

  const auto to_pixel = [&](const Vec2& p) {
    return cv::Point(static_cast<int>(std::lround(p.x() / metres_per_pixel)),
                     static_cast<int>(std::lround(-p.y() / metres_per_pixel)));
  };
  const int touch_radius = std::max(2, static_cast<int>(std::lround(kTouchRadiusM / metres_per_pixel)));
  for (const Vec2& touch : overlay.touches) {
    cv::circle(screen, to_pixel(touch), touch_radius, cv::Scalar(250, 250, 250), cv::FILLED, cv::LINE_AA);
    cv::circle(screen, to_pixel(touch), touch_radius, cv::Scalar(60, 60, 60), std::max(1, touch_radius / 5), cv::LINE_AA);
  }
  if (overlay.robot_hand) {
    const int r = std::max(3, static_cast<int>(std::lround(kRobotRadiusM / metres_per_pixel)));
    const cv::Point p = to_pixel(*overlay.robot_hand);
    const int thickness = std::max(1, r / 5);
    const cv::Scalar orange = bgr_of(PaletteColour::Orange) * 0.8;
    cv::circle(screen, p, r, orange, thickness, cv::LINE_AA);
    cv::line(screen, p - cv::Point(r + r / 2, 0), p + cv::Point(r + r / 2, 0), orange, thickness, cv::LINE_AA);
    cv::line(screen, p - cv::Point(0, r + r / 2), p + cv::Point(0, r + r / 2), orange, thickness, cv::LINE_AA);
    cv::circle(screen, p, std::max(1, r / 4), orange, cv::FILLED, cv::LINE_AA);
  }
  return screen;
}

void draw_zones(cv::Mat& screen, const ZoneMap& zones, bool labels) {
  if (screen.empty() || screen.type() != CV_8UC3) {
    throw InputError("the screen image is empty or not 8-bit BGR", "screen", "a BGR CV_8UC3 image");
  }
  const double pixels_per_metre = screen.cols / kScreenWidthM;
  const int thickness = std::max(1, screen.cols / 640);
  const auto to_pixel = [&](const Vec2& p) {
    return cv::Point(static_cast<int>(std::lround(p.x() * pixels_per_metre)),
                     static_cast<int>(std::lround(-p.y() * pixels_per_metre)));
  };
  for (const Zone& zone : zones.zones()) {
    std::vector<cv::Point> outline;
    for (const Vec2& p : zone.polygon) outline.push_back(to_pixel(p));
    const auto rgb = zone_marker_rgb(zone.colour);
    const cv::Scalar colour(rgb[2], rgb[1], rgb[0]);
    cv::polylines(screen, std::vector<std::vector<cv::Point>>{outline}, true, cv::Scalar(20, 20, 20), thickness + 2,
                  cv::LINE_AA);
    cv::polylines(screen, std::vector<std::vector<cv::Point>>{outline}, true, colour, thickness, cv::LINE_AA);
  }
  if (!labels) return;
  const double font_scale = 0.5 * screen.cols / 960.0;
  for (const Zone& zone : zones.zones()) {
    const std::string text = zone.colour + " " + std::to_string(zone.id);
    int baseline = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, font_scale, thickness, &baseline);
    const cv::Point origin = to_pixel(zone.centroid) - cv::Point(size.width / 2, -size.height / 2);
    cv::putText(screen, text, origin, cv::FONT_HERSHEY_SIMPLEX, font_scale, cv::Scalar(255, 255, 255), thickness + 2,
                cv::LINE_AA);
    cv::putText(screen, text, origin, cv::FONT_HERSHEY_SIMPLEX, font_scale, cv::Scalar(0, 0, 0), thickness, cv::LINE_AA);
  }
}

}  // namespace freeplay::sim
