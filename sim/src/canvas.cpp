// The drawing layer: 50 px round strokes with quadratic smoothing between midpoints, as the real QML Canvas.

#include "freeplay/sim/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <opencv2/imgproc.hpp>

#include "freeplay/core/error.hpp"

namespace freeplay::sim {
namespace {

constexpr double kCurveStepPx = 4.0;  // spacing of the samples of a quadratic segment
constexpr int kMaxCurveSamples = 32;

cv::Vec3b bgr_of(PaletteColour colour) {
  const auto rgb = palette_rgb(colour);
  return {static_cast<std::uint8_t>(rgb[2]), static_cast<std::uint8_t>(rgb[1]), static_cast<std::uint8_t>(rgb[0])};
}

/// Samples the quadratic Bézier from `a` with control `c` to `b` into `out` (both ends included).
void quadratic(const cv::Point2d& a, const cv::Point2d& c, const cv::Point2d& b, std::vector<cv::Point2d>& out) {
  const double length = cv::norm(c - a) + cv::norm(b - c);
  const int samples = std::clamp(static_cast<int>(std::ceil(length / kCurveStepPx)), 1, kMaxCurveSamples);
  out.clear();
  for (int i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples;
    const double u = 1.0 - t;
    out.push_back(u * u * a + 2.0 * u * t * c + t * t * b);
  }
}

}  // namespace

DrawingCanvas::DrawingCanvas(int width_px)
    : background_(shared_background(BackgroundKind::Blank, width_px)),
      image_(background_.clone()),
      stroke_width_px_(std::max(1, static_cast<int>(std::lround(kStrokeWidthPx * width_px /
                                                                 static_cast<double>(kScreenWidthPx))))),
      unpublished_(image_.rows) {
  unpublished_.add(cv::Rect(0, 0, image_.cols, image_.rows));
}

void DrawingCanvas::set_background(BackgroundKind kind) {
  cv::Mat fresh = shared_background(kind, image_.cols);  // read only: strokes go into image_
  kind_ = kind;
  background_ = std::move(fresh);
  background_.copyTo(image_);
  strokes_.clear();
  touch(cv::Rect(0, 0, image_.cols, image_.rows));
}

cv::Point2d DrawingCanvas::to_pixel(const Vec2& p) const {
  const double metres_per_pixel = kScreenWidthM / image_.cols;
  return {p.x() / metres_per_pixel, -p.y() / metres_per_pixel};
}

void DrawingCanvas::begin_stroke(int stroke_id, PaletteColour colour, const Vec2& p) {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
    throw InputError("stroke position is not finite", "stroke position", "finite sandtray coordinates (m)");
  }
  if (!strokes_.contains(stroke_id) && strokes_.size() >= static_cast<std::size_t>(kMaxTouches)) {
    throw InputError("too many simultaneous strokes for stroke id " + std::to_string(stroke_id), "stroke_id",
                     "at most " + std::to_string(kMaxTouches) + " active strokes");
  }
  const cv::Point2d start = to_pixel(p);
  strokes_[stroke_id] = Stroke{colour, start, start};
  paint_path({start}, colour);
}

void DrawingCanvas::extend_stroke(int stroke_id, const Vec2& p) {
  const auto it = strokes_.find(stroke_id);
  if (it == strokes_.end()) {
    throw InputError("no active stroke with id " + std::to_string(stroke_id), "stroke_id",
                     "an id passed to begin_stroke and not yet ended");
  }
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
    throw InputError("stroke position is not finite", "stroke position", "finite sandtray coordinates (m)");
  }
  Stroke& stroke = it->second;
  const cv::Point2d point = to_pixel(p);
  if (cv::norm(point - stroke.last_point) < 0.5) return;
  const cv::Point2d mid = 0.5 * (stroke.last_point + point);
  quadratic(stroke.last_mid, stroke.last_point, mid, piece_);
  paint_path(piece_, stroke.colour);
  stroke.last_mid = mid;
  stroke.last_point = point;
}

void DrawingCanvas::end_stroke(int stroke_id) {
  const auto it = strokes_.find(stroke_id);
  if (it == strokes_.end()) return;
  const Stroke stroke = it->second;
  strokes_.erase(it);
  if (cv::norm(stroke.last_point - stroke.last_mid) >= 0.5) {
    paint_path({stroke.last_mid, stroke.last_point}, stroke.colour);
  }
}

void DrawingCanvas::clear_strokes() {
  background_.copyTo(image_);
  for (auto& [id, stroke] : strokes_) stroke.last_mid = stroke.last_point;
  touch(cv::Rect(0, 0, image_.cols, image_.rows));
}

void DrawingCanvas::paint_path(const std::vector<cv::Point2d>& path, PaletteColour colour) {
  const double radius = 0.5 * stroke_width_px_ + 2.0;
  double min_x = path.front().x, max_x = min_x, min_y = path.front().y, max_y = min_y;
  for (const auto& p : path) {
    min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
  }
  const cv::Rect bounds(cv::Point(static_cast<int>(std::floor(min_x - radius)), static_cast<int>(std::floor(min_y - radius))),
                        cv::Point(static_cast<int>(std::ceil(max_x + radius)) + 1, static_cast<int>(std::ceil(max_y + radius)) + 1));
  const cv::Rect roi = bounds & cv::Rect(0, 0, image_.cols, image_.rows);
  if (roi.empty()) return;  // entirely off the canvas
  local_path_.clear();
  for (const auto& p : path) local_path_.emplace_back(p.x - roi.x, p.y - roi.y);
  cv::Mat target = image_(roi);
  if (colour == PaletteColour::Eraser) {
    painter_.erase(target, background_(roi), local_path_, stroke_width_px_);  // destination-out
  } else {
    painter_.paint(target, local_path_, stroke_width_px_, bgr_of(colour));
  }
  touch(roi);
}

void DrawingCanvas::touch(const cv::Rect& changed) {
  dirty_ = true;
  unpublished_.add(changed);
  hash_cache_.reset();
}

double DrawingCanvas::coverage() const { return differing_pixel_share(image_, background_); }

double differing_pixel_share(const cv::Mat& image, const cv::Mat& background) {
  if (image.type() != CV_8UC3 || background.type() != CV_8UC3 || image.size() != background.size() || image.empty()) {
    throw InputError("comparing a drawing needs two BGR images of one size", "image", "CV_8UC3, same size");
  }
  std::size_t differing = 0;
  for (int row = 0; row < image.rows; ++row) {
    const auto* a = image.ptr<cv::Vec3b>(row);
    const auto* b = background.ptr<cv::Vec3b>(row);
    for (int col = 0; col < image.cols; ++col) differing += a[col] != b[col] ? 1u : 0u;
  }
  return static_cast<double>(differing) / static_cast<double>(image.total());
}

std::uint64_t DrawingCanvas::hash() const {
  if (hash_cache_) return *hash_cache_;
  // 64-bit multiply-xorshift over 8-byte words of every row (rows may be padded in general).
  std::uint64_t h = 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint64_t>(kind_);
  const auto mix = [&h](std::uint64_t word) {
    h ^= word + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
  };
  const std::size_t row_bytes = static_cast<std::size_t>(image_.cols) * image_.elemSize();
  for (int row = 0; row < image_.rows; ++row) {
    const unsigned char* data = image_.ptr<unsigned char>(row);
    std::size_t i = 0;
    for (; i + 8 <= row_bytes; i += 8) {
      std::uint64_t word;
      std::memcpy(&word, data + i, 8);
      mix(word);
    }
    std::uint64_t tail = 0;
    std::memcpy(&tail, data + i, row_bytes - i);
    mix(tail);
  }
  hash_cache_ = h;
  return h;
}

}  // namespace freeplay::sim
