// Colour zones with the pipeline of the real `zones_from_image` node (core:nodes/zones_from_image, reference §2.9).

#include "freeplay/sim/zones.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <opencv2/imgproc.hpp>

#include "freeplay/core/error.hpp"

namespace freeplay::sim {
namespace {

struct ColourRange {
  std::string_view colour;
  HsvRange range;
};

// The real node's ranges (lower → upper, OpenCV HSV units), in kZoneColours order.
constexpr std::array<ColourRange, 7> kRanges = {{
    {"green", {{40, 0, 70}, {70, 255, 230}}},
    {"blue", {{70, 0, 70}, {130, 255, 230}}},
    {"yellow", {{1, 100, 0}, {40, 255, 255}}},
    {"white", {{0, 0, 180}, {255, 60, 255}}},
    {"black", {{0, 0, 0}, {255, 60, 70}}},
    {"purple", {{120, 0, 70}, {255, 255, 230}}},
    {"red", {{0, 120, 70}, {10, 255, 255}}},
}};

std::string colour_list() {
  std::string out;
  for (const auto c : kZoneColours) out += (out.empty() ? "" : ", ") + std::string(c);
  return out;
}

const ColourRange& range_of(std::string_view colour) {
  for (const auto& r : kRanges) {
    if (r.colour == colour) return r;
  }
  throw InputError("unknown zone colour '" + std::string(colour) + "'", "colour", colour_list());
}

/// The real node's colour mask of the downsampled HSV image.
void mask_of(const cv::Mat& small_hsv, const HsvRange& range, cv::Mat& mask) {
  cv::inRange(small_hsv, cv::Scalar(range.lower[0], range.lower[1], range.lower[2]),
              cv::Scalar(range.upper[0], range.upper[1], range.upper[2]), mask);
}

/// The real node's mask → contour steps (opening, dilation, distance-transform threshold, contours).
std::vector<std::vector<cv::Point>> contours_of(const cv::Mat& colour_mask) {
  static const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  cv::Mat mask;
  cv::morphologyEx(colour_mask, mask, cv::MORPH_OPEN, kernel, cv::Point(-1, -1), 2);
  if (cv::countNonZero(mask) == 0) return {};  // nothing of this colour: the remaining steps find no contour
  cv::dilate(mask, mask, kernel);
  cv::Mat distance;
  cv::distanceTransform(mask, distance, cv::DIST_L2, cv::DIST_MASK_5);
  double max_distance = 0.0;
  cv::minMaxLoc(distance, nullptr, &max_distance);
  cv::Mat foreground;
  cv::threshold(distance, foreground, 0.25 * max_distance, 255.0, cv::THRESH_BINARY);
  foreground.convertTo(foreground, CV_8U);
  cv::dilate(foreground, foreground, kernel, cv::Point(-1, -1), 2);
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(foreground, contours, hierarchy, cv::RETR_TREE, cv::CHAIN_APPROX_TC89_KCOS);
  return contours;
}

bool same_pixels(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return false;
  for (int row = 0; row < a.rows; ++row) {
    if (std::memcmp(a.ptr(row), b.ptr(row), static_cast<std::size_t>(a.cols) * a.elemSize()) != 0) return false;
  }
  return true;
}

std::uint64_t hash_of(const cv::Mat& mask) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (int row = 0; row < mask.rows; ++row) {
    const auto* p = mask.ptr<unsigned char>(row);
    const std::size_t bytes = static_cast<std::size_t>(mask.cols) * mask.elemSize();
    std::size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
      std::uint64_t word;
      std::memcpy(&word, p + i, 8);
      h = (h ^ word) * 0x100000001b3ULL;
      h ^= h >> 29;
    }
    for (; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
  }
  return h;
}

/// Contours of the masks this thread segmented recently (every episode starts with the same few backgrounds):
/// a mask seen before is not segmented again. Contours are a pure function of the mask, so this changes nothing.
class MaskMemo {
 public:
  const std::vector<std::vector<cv::Point>>* find(std::uint64_t hash, const cv::Mat& mask) const {
    for (const auto& e : entries_) {
      if (e.hash == hash && same_pixels(e.mask, mask)) return &e.contours;
    }
    return nullptr;
  }
  void add(std::uint64_t hash, const cv::Mat& mask, const std::vector<std::vector<cv::Point>>& contours) {
    Entry& e = entries_.size() < kCapacity ? entries_.emplace_back() : entries_[next_++ % kCapacity];
    e.hash = hash;
    mask.copyTo(e.mask);
    e.contours = contours;
  }

 private:
  static constexpr std::size_t kCapacity = 32;
  struct Entry {
    std::uint64_t hash = 0;
    cv::Mat mask;
    std::vector<std::vector<cv::Point>> contours;
  };
  std::vector<Entry> entries_;
  std::size_t next_ = 0;
};

/// The source rows a bilinear resize from `rows` to `height` reads. OpenCV computes the source row in single
/// precision; the rows of both roundings are marked (with a one-row margin).
std::vector<char> rows_read_by_resize(int rows, int height) {
  std::vector<char> needed(static_cast<std::size_t>(rows), 0);
  const double scale_y = static_cast<double>(rows) / height;
  for (int dy = 0; dy < height; ++dy) {
    const int sy_double = static_cast<int>(std::floor((dy + 0.5) * scale_y - 0.5));
    const int sy_float = static_cast<int>(std::floor(static_cast<float>((dy + 0.5) * scale_y - 0.5)));
    for (const int sy : {sy_double, sy_float}) {
      for (int y = sy; y <= sy + 1; ++y) needed[static_cast<std::size_t>(std::clamp(y, 0, rows - 1))] = 1;
    }
  }
  return needed;
}

}  // namespace

HsvRange zone_hsv_range(std::string_view colour) { return range_of(colour).range; }

std::array<unsigned char, 3> zone_marker_rgb(std::string_view colour) {
  const HsvRange range = zone_hsv_range(colour);
  cv::Mat hsv(1, 1, CV_8UC3);
  // H is clamped to OpenCV's 0–179 before conversion (the upper bound 255 of several ranges is out of range).
  auto mid = [&](int i) { return (range.lower[static_cast<std::size_t>(i)] + range.upper[static_cast<std::size_t>(i)]) / 2; };
  hsv.at<cv::Vec3b>(0, 0) = cv::Vec3b(static_cast<unsigned char>(std::min(mid(0), 179)),
                                      static_cast<unsigned char>(mid(1)), static_cast<unsigned char>(mid(2)));
  cv::Mat rgb;
  cv::cvtColor(hsv, rgb, cv::COLOR_HSV2RGB);
  const cv::Vec3b p = rgb.at<cv::Vec3b>(0, 0);
  return {p[0], p[1], p[2]};
}

ZoneMap ZoneMap::segment(const cv::Mat& bgr, double metres_per_pixel) {
  return ZoneSegmenter().segment(bgr, metres_per_pixel);
}

// BGR → HSV, then a bilinear resize (the real node's order). Bilinear interpolation reads only the two source rows
// around each destination row, so only those rows are converted; the others stay zero and are never read. The
// result is identical to converting the whole image.
void ZoneSegmenter::convert_rows(const cv::Mat& bgr, const cv::Rect& region) {
  for (int y = region.y; y < region.y + region.height;) {
    if (!needed_[static_cast<std::size_t>(y)]) {
      ++y;
      continue;
    }
    int end = y;
    while (end < region.y + region.height && needed_[static_cast<std::size_t>(end)]) ++end;
    const cv::Range rows(y, end);
    const cv::Range cols(region.x, region.x + region.width);
    cv::Mat target = hsv_(rows, cols);
    cv::cvtColor(bgr(rows, cols), target, cv::COLOR_BGR2HSV);
    y = end;
  }
}

ZoneMap ZoneSegmenter::segment(const cv::Mat& bgr, double metres_per_pixel, std::optional<cv::Rect> changed) {
  if (bgr.empty()) throw InputError("the image is empty", "image", "a BGR CV_8UC3 image");
  if (bgr.type() != CV_8UC3) {
    throw InputError("the image has OpenCV type " + std::to_string(bgr.type()), "image", "a BGR CV_8UC3 image");
  }
  if (!(metres_per_pixel > 0.0) || !std::isfinite(metres_per_pixel)) {
    throw InputError("metres per pixel must be positive", "metres_per_pixel", "> 0");
  }
  const int small_height =
      std::max(1, static_cast<int>(std::lround(static_cast<double>(bgr.rows) * kZoneSegmentationWidthPx / bgr.cols)));
  const cv::Rect whole(0, 0, bgr.cols, bgr.rows);
  if (hsv_.size() != bgr.size()) {
    hsv_ = cv::Mat::zeros(bgr.size(), CV_8UC3);
    needed_ = rows_read_by_resize(bgr.rows, small_height);
    changed = whole;
  }
  convert_rows(bgr, changed ? (*changed & whole) : whole);
  cv::resize(hsv_, small_hsv_, cv::Size(kZoneSegmentationWidthPx, small_height), 0, 0, cv::INTER_LINEAR);
  const double scale_x = static_cast<double>(bgr.cols) / kZoneSegmentationWidthPx;
  const double scale_y = static_cast<double>(bgr.rows) / small_height;
  ++counters_.images;

  ZoneMap map;
  for (std::size_t c = 0; c < kRanges.size(); ++c) {
    const auto& entry = kRanges[c];
    auto& cached = cache_[c];
    mask_of(small_hsv_, entry.range, mask_);
    if (same_pixels(mask_, cached.mask)) {
      ++counters_.masks_reused;
    } else {
      thread_local MaskMemo memo;
      mask_.copyTo(cached.mask);
      const std::uint64_t hash = hash_of(cached.mask);
      if (const auto* known = memo.find(hash, cached.mask)) {
        ++counters_.masks_reused;
        cached.contours = *known;
      } else {
        ++counters_.masks_recomputed;
        cached.contours = contours_of(cached.mask);
        memo.add(hash, cached.mask, cached.contours);
      }
    }
    int id = 0;
    for (const auto& contour : cached.contours) {
      Zone zone;
      zone.colour = std::string(entry.colour);
      zone.id = id++;
      zone.polygon.reserve(contour.size());
      for (const auto& p : contour) {
        zone.polygon.emplace_back(p.x * scale_x * metres_per_pixel, -p.y * scale_y * metres_per_pixel);
      }
      zone.centroid = vertex_mean(zone.polygon);
      zone.area_m2 = std::abs(signed_area(zone.polygon));
      map.zones_.push_back(std::move(zone));
    }
  }
  return map;
}

std::vector<const Zone*> ZoneMap::of_colour(std::string_view colour) const {
  range_of(colour);
  std::vector<const Zone*> out;
  for (const auto& zone : zones_) {
    if (zone.colour == colour) out.push_back(&zone);
  }
  return out;
}

const Zone* ZoneMap::at(const Vec2& p) const {
  const Zone* best = nullptr;
  double best_area = std::numeric_limits<double>::infinity();
  for (const auto& zone : zones_) {
    if (zone.polygon.size() >= 3 && zone.area_m2 < best_area && point_in_polygon(zone.polygon, p)) {
      best = &zone;
      best_area = zone.area_m2;
    }
  }
  return best;
}

std::size_t ZoneMap::count(std::string_view colour) const {
  range_of(colour);
  return static_cast<std::size_t>(
      std::count_if(zones_.begin(), zones_.end(), [&](const Zone& z) { return z.colour == colour; }));
}

}  // namespace freeplay::sim
