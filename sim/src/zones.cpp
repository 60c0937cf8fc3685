// Colour zones with the pipeline of the real `zones_from_image` node (core:nodes/zones_from_image, reference §2.9).

#include "freeplay/sim/zones.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>

#include <opencv2/imgproc.hpp>
#include <opencv2/imgproc/hal/hal.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/sim/zone_raster.hpp"

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

/// Bounding box of the pixels where two images of one size and type differ (empty when none).
cv::Rect differing_rect(const cv::Mat& a, const cv::Mat& b) {
  const std::size_t row_bytes = static_cast<std::size_t>(a.cols) * a.elemSize();
  int y0 = -1, y1 = -1;
  for (int y = 0; y < a.rows; ++y) {
    if (std::memcmp(a.ptr(y), b.ptr(y), row_bytes) == 0) continue;
    if (y0 < 0) y0 = y;
    y1 = y;
  }
  if (y0 < 0) return {};
  // Byte by byte: the first differing byte from the left (right) lies in the first (last) differing pixel.
  const std::size_t channels = a.elemSize();
  std::size_t x0 = static_cast<std::size_t>(a.cols);
  std::size_t x1_end = 0;  // one past the last differing pixel found so far
  for (int y = y0; y <= y1; ++y) {
    const unsigned char* p = a.ptr(y);
    const unsigned char* q = b.ptr(y);
    for (std::size_t i = 0; i < x0 * channels; ++i) {
      if (p[i] != q[i]) {
        x0 = i / channels;
        break;
      }
    }
    for (std::size_t i = row_bytes; i > x1_end * channels; --i) {
      if (p[i - 1] != q[i - 1]) {
        x1_end = (i - 1) / channels + 1;
        break;
      }
    }
  }
  const int x1 = static_cast<int>(x1_end) - 1;
  return {static_cast<int>(x0), y0, x1 - static_cast<int>(x0) + 1, y1 - y0 + 1};
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

/// The HSV conversions of whole images this thread made recently, full-size and downsampled (every episode shows the
/// same few backgrounds): an image seen before is not converted and downsampled again. Both are pure functions of
/// the image; the full-size one is shared with the segmenter that recalls it until it writes into it.
class ConversionMemo {
 public:
  struct Entry {
    cv::Mat bgr;
    cv::Mat hsv;
    cv::Mat small_hsv;
  };
  const Entry* find(const cv::Mat& bgr) const {
    for (const auto& e : entries_) {
      if (same_pixels(e.bgr, bgr)) return &e;
    }
    return nullptr;
  }
  void add(const cv::Mat& bgr, const cv::Mat& hsv, const cv::Mat& small_hsv) {
    Entry& e = entries_.size() < kCapacity ? entries_.emplace_back() : entries_[next_++ % kCapacity];
    e.bgr = bgr.clone();
    e.hsv = hsv.clone();
    e.small_hsv = small_hsv.clone();
  }

 private:
  static constexpr std::size_t kCapacity = 8;
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

namespace detail {
namespace {

/// Whether resizing `roi` of `image` alone to `target` (a block of `whole`) gives exactly that block of `whole`.
bool resizes_alone_exactly(const cv::Mat& image, const cv::Rect& roi, const cv::Mat& whole, const cv::Rect& target) {
  cv::Mat block;
  cv::resize(image(roi), block, target.size(), 0, 0, cv::INTER_LINEAR);
  return cv::norm(whole(target), block, cv::NORM_INF) == 0.0;
}

}  // namespace

/// The tiles of the downsampled image that a bilinear resize of their own source block gives exactly as the whole
/// resize does (the same scale, taps inside the block): `band_rows` rows by `tile_cols` columns, or whole rows
/// (columns) when no smaller tile does. OpenCV's resize computes each axis's source index and fixed-point weight from
/// the destination index alone, so a block is exact when every single band (tile) is, and every run of tiles is when
/// the runs that start at the first tile are (a run's weights are those of the run of its length at the start).
/// Checked once per size on a random image, so an OpenCV whose rounding differs falls back to whole resizes.
ResizeTiles resize_tiles(const cv::Size& source, const cv::Size& small) {
  thread_local cv::Size checked_source;
  thread_local cv::Size checked_small;
  thread_local ResizeTiles checked;
  if (source == checked_source && small == checked_small) return checked;
  checked_source = source;
  checked_small = small;
  checked = {small.height, small.width};
  cv::Mat image(source, CV_8UC3);
  cv::RNG rng(17);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  cv::Mat whole;
  cv::resize(image, whole, small, 0, 0, cv::INTER_LINEAR);
  const int row_groups = std::gcd(source.height, small.height);
  if (row_groups > 1) {
    const int band_rows = small.height / row_groups;
    const int source_rows = source.height / row_groups;
    bool exact = true;
    for (int band = 0; band < row_groups && exact; ++band) {
      exact = resizes_alone_exactly(image, cv::Rect(0, band * source_rows, source.width, source_rows), whole,
                                    cv::Rect(0, band * band_rows, small.width, band_rows));
    }
    if (exact) checked.band_rows = band_rows;
  }
  const int col_groups = std::gcd(source.width, small.width);
  if (col_groups > 1) {
    const int tile_cols = small.width / col_groups;
    const int source_cols = source.width / col_groups;
    const int rows = checked.band_rows;
    const int source_rows = source.height * rows / small.height;
    bool exact = true;
    for (int tile = 0; tile < col_groups && exact; ++tile) {
      exact = resizes_alone_exactly(image, cv::Rect(tile * source_cols, 0, source_cols, source_rows), whole,
                                    cv::Rect(tile * tile_cols, 0, tile_cols, rows));
    }
    for (int tiles = 2; tiles < col_groups && exact; ++tiles) {
      exact = resizes_alone_exactly(image, cv::Rect(0, 0, tiles * source_cols, source_rows), whole,
                                    cv::Rect(0, 0, tiles * tile_cols, rows));
    }
    if (exact) checked.tile_cols = tile_cols;
  }
  return checked;
}

}  // namespace detail

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

namespace {

// Checks the segmenters' input (a BGR image, a positive scale) and returns the height of its 200-px-wide copy.
int checked_small_height(const cv::Mat& bgr, double metres_per_pixel) {
  if (bgr.empty()) throw InputError("the image is empty", "image", "a BGR CV_8UC3 image");
  if (bgr.type() != CV_8UC3) {
    throw InputError("the image has OpenCV type " + std::to_string(bgr.type()), "image", "a BGR CV_8UC3 image");
  }
  if (!(metres_per_pixel > 0.0) || !std::isfinite(metres_per_pixel)) {
    throw InputError("metres per pixel must be positive", "metres_per_pixel", "> 0");
  }
  const int small_height =
      std::max(1, static_cast<int>(std::lround(static_cast<double>(bgr.rows) * kZoneSegmentationWidthPx / bgr.cols)));
  return small_height;
}

}  // namespace

ZoneMap ZoneMap::segment(const cv::Mat& bgr, double metres_per_pixel) {
  const int small_height = checked_small_height(bgr, metres_per_pixel);
  cv::Mat hsv;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  cv::Mat small_hsv;
  cv::resize(hsv, small_hsv, cv::Size(kZoneSegmentationWidthPx, small_height), 0, 0, cv::INTER_LINEAR);
  const double scale_x = static_cast<double>(bgr.cols) / kZoneSegmentationWidthPx;
  const double scale_y = static_cast<double>(bgr.rows) / small_height;
  ZoneMap map;
  for (const auto& entry : kRanges) {
    cv::Mat mask;
    cv::inRange(small_hsv, cv::Scalar(entry.range.lower[0], entry.range.lower[1], entry.range.lower[2]),
                cv::Scalar(entry.range.upper[0], entry.range.upper[1], entry.range.upper[2]), mask);
    map.add_zones(entry.colour, detail::reference_contours(mask), scale_x, scale_y, metres_per_pixel);
  }
  return map;
}

void ZoneMap::add_zones(std::string_view colour, const std::vector<std::vector<cv::Point>>& contours, double scale_x,
                        double scale_y, double metres_per_pixel) {
  int id = 0;
  for (const auto& contour : contours) {
    Zone zone;
    zone.colour = std::string(colour);
    zone.id = id++;
    zone.polygon.reserve(contour.size());
    for (const auto& p : contour) {
      zone.polygon.emplace_back(p.x * scale_x * metres_per_pixel, -p.y * scale_y * metres_per_pixel);
    }
    zone.centroid = vertex_mean(zone.polygon);
    zone.area_m2 = std::abs(signed_area(zone.polygon));
    zones_.push_back(std::move(zone));
  }
}

cv::Range ZoneSegmenter::converted_columns(int y, const cv::Rect& region, const ChangedPixels* rows) {
  const cv::Range columns(region.x, region.x + region.width);
  if (rows == nullptr) return columns;
  const cv::Range changed = rows->columns(y);
  const int start = std::max(columns.start, changed.start);
  const int end = std::min(columns.end, changed.end);
  return start < end ? cv::Range(start, end) : cv::Range(0, 0);  // cv::Range::empty() is start == end only
}

// BGR → HSV, then a bilinear resize (the real node's order). Bilinear interpolation reads only the two source rows
// around each destination row, so only those rows are converted; the others stay zero and are never read. The
// result is identical to converting the whole image.
void ZoneSegmenter::convert_rows(const cv::Mat& bgr, const cv::Rect& region, const ChangedPixels* rows) {
  if (hsv_shared_) {
    hsv_ = hsv_.clone();
    hsv_shared_ = false;
  }
  for (int y = region.y; y < region.y + region.height;) {
    if (!needed_[static_cast<std::size_t>(y)]) {
      ++y;
      continue;
    }
    // A run of needed rows with the same columns is converted in one call.
    const cv::Range cols = converted_columns(y, region, rows);
    int end = y + 1;
    while (end < region.y + region.height && needed_[static_cast<std::size_t>(end)] &&
           converted_columns(end, region, rows) == cols) {
      ++end;
    }
    if (!cols.empty()) {
      // OpenCV's BGR → HSV (what cv::cvtColor with COLOR_BGR2HSV runs) without its per-call array checks.
      const cv::Mat source = bgr(cv::Range(y, end), cols);
      cv::Mat target = hsv_(cv::Range(y, end), cols);
      cv::hal::cvtBGRtoHSV(source.data, source.step, target.data, target.step, cols.size(), end - y, CV_8U, 3,
                           false, false, true);
    }
    y = end;
  }
}

ZoneSegmenter::ZoneSegmenter() {
  for (auto& raster : rasters_) raster = std::make_unique<detail::ColourRaster>();
}

ZoneSegmenter::~ZoneSegmenter() = default;

namespace {

// For each of H, S and V and each 8-bit value, the colours whose range holds it (bit c for kRanges[c]): a pixel lies
// in colour c's range exactly when bit c is set in all three of its channels' entries (cv::inRange, per channel).
using ChannelBits = std::array<std::array<std::uint8_t, 256>, 3>;
static_assert(kRanges.size() <= 8, "one bit per colour in a byte");

const ChannelBits& channel_bits() {
  static const ChannelBits bits = [] {
    ChannelBits b{};
    for (std::size_t c = 0; c < kRanges.size(); ++c) {
      for (std::size_t channel = 0; channel < 3; ++channel) {
        for (int v = 0; v < 256; ++v) {
          if (kRanges[c].range.lower[channel] <= v && v <= kRanges[c].range.upper[channel]) {
            b[channel][static_cast<std::size_t>(v)] |= static_cast<std::uint8_t>(1U << c);
          }
        }
      }
    }
    return b;
  }();
  return bits;
}

}  // namespace

std::array<cv::Rect, kZoneColours.size()> ZoneSegmenter::update_masks(const cv::Rect& region) {
  constexpr std::size_t kColours = kZoneColours.size();
  const ChannelBits& bits = channel_bits();
  std::array<cv::Point, kColours> low;
  std::array<cv::Point, kColours> high;
  low.fill({region.x + region.width, region.y + region.height});
  high.fill({-1, -1});
  std::array<unsigned char*, kColours> rows{};
  for (int y = region.y; y < region.y + region.height; ++y) {
    const auto* hsv = small_hsv_.ptr<cv::Vec3b>(y);
    for (std::size_t c = 0; c < kColours; ++c) rows[c] = rasters_[c]->mask().ptr<unsigned char>(y);
    for (int x = region.x; x < region.x + region.width; ++x) {
      const cv::Vec3b p = hsv[x];
      const unsigned inside = bits[0][p[0]] & bits[1][p[1]] & bits[2][p[2]];
      for (std::size_t c = 0; c < kColours; ++c) {
        const unsigned char value = (inside >> c) & 1U ? 255 : 0;  // cv::inRange
        if (rows[c][x] == value) continue;
        rows[c][x] = value;
        low[c] = {std::min(low[c].x, x), std::min(low[c].y, y)};
        high[c] = {std::max(high[c].x, x), std::max(high[c].y, y)};
      }
    }
  }
  std::array<cv::Rect, kColours> changed;
  for (std::size_t c = 0; c < kColours; ++c) {
    if (high[c].x >= 0) changed[c] = cv::Rect(low[c], high[c] + cv::Point(1, 1));
  }
  return changed;
}

ZoneMap ZoneSegmenter::segment(const cv::Mat& bgr, double metres_per_pixel, std::optional<cv::Rect> changed) {
  return segment_changes(bgr, metres_per_pixel, changed, nullptr);
}

ZoneMap ZoneSegmenter::segment(const cv::Mat& bgr, double metres_per_pixel, const ChangedPixels& changed) {
  // Rows of another image than `bgr` say nothing about its rows: then only the box is used.
  return segment_changes(bgr, metres_per_pixel, changed.box(), changed.row_count() == bgr.rows ? &changed : nullptr);
}

ZoneMap ZoneSegmenter::segment_changes(const cv::Mat& bgr, double metres_per_pixel, std::optional<cv::Rect> changed,
                                       const ChangedPixels* rows) {
  const int small_height = checked_small_height(bgr, metres_per_pixel);
  const cv::Rect whole(0, 0, bgr.cols, bgr.rows);
  const cv::Size small_size(kZoneSegmentationWidthPx, small_height);
  // A whole image reported as changed is a new background, which recurs (every episode shows the same few): it is
  // recalled from, or kept in, the thread's memo. An image segmented without a report is not kept.
  const bool new_background = changed.has_value() && (*changed & whole) == whole;
  if (hsv_.size() != bgr.size()) {
    hsv_ = cv::Mat::zeros(bgr.size(), CV_8UC3);
    hsv_shared_ = false;
    needed_ = rows_read_by_resize(bgr.rows, small_height);
    tiles_ = detail::resize_tiles(bgr.size(), small_size);
    changed = whole;
    rows = nullptr;
  }
  const cv::Rect converted = changed ? (*changed & whole) : whole;
  if (converted == whole) rows = nullptr;  // every needed pixel is converted again
  // A new background this thread converted before is recalled instead.
  thread_local ConversionMemo conversions;
  const ConversionMemo::Entry* recalled = new_background ? conversions.find(bgr) : nullptr;
  if (recalled != nullptr) {
    hsv_ = recalled->hsv;
    hsv_shared_ = true;
    ++counters_.images_recalled;
  } else {
    convert_rows(bgr, converted, rows);
  }
  if (small_hsv_.size() != small_size) {
    std::swap(small_hsv_, previous_small_);
    if (recalled != nullptr) {
      recalled->small_hsv.copyTo(small_hsv_);
    } else {
      cv::resize(hsv_, small_hsv_, small_size, 0, 0, cv::INTER_LINEAR);
    }
    resized_ = cv::Rect(cv::Point(0, 0), small_size);
  } else {
    // previous_small_ equals small_hsv_ except where the last call resized: that is brought over, and it is the
    // image before this one again.
    if (previous_small_.size() != small_size) {
      small_hsv_.copyTo(previous_small_);
    } else if (!resized_.empty()) {
      small_hsv_(resized_).copyTo(previous_small_(resized_));
    }
    // Only the tiles whose source pixels were converted again (all of them for a recalled image): the run of tiles
    // across the converted columns, in each band of rows across the converted rows.
    resized_ = cv::Rect();
    if (recalled != nullptr) {
      recalled->small_hsv.copyTo(small_hsv_);
      resized_ = cv::Rect(cv::Point(0, 0), small_size);
    } else if (!converted.empty()) {
      const int source_rows = bgr.rows * tiles_.band_rows / small_height;
      const int source_cols = bgr.cols * tiles_.tile_cols / small_size.width;
      const int first_band = converted.y / source_rows;
      const int end_band = (converted.y + converted.height - 1) / source_rows + 1;
      for (int band = first_band; band < end_band; ++band) {
        // The columns converted in this band's needed rows.
        int from = bgr.cols;
        int to = 0;
        const int row_end = std::min((band + 1) * source_rows, converted.y + converted.height);
        for (int y = std::max(band * source_rows, converted.y); y < row_end; ++y) {
          if (!needed_[static_cast<std::size_t>(y)]) continue;
          const cv::Range cols = converted_columns(y, converted, rows);
          if (cols.empty()) continue;
          from = std::min(from, cols.start);
          to = std::max(to, cols.end);
        }
        if (from >= to) continue;
        const int first_tile = from / source_cols;
        const int end_tile = (to - 1) / source_cols + 1;
        const cv::Rect tiles(first_tile * tiles_.tile_cols, band * tiles_.band_rows,
                             (end_tile - first_tile) * tiles_.tile_cols, tiles_.band_rows);
        cv::Mat target = small_hsv_(tiles);
        cv::resize(hsv_(cv::Rect(first_tile * source_cols, band * source_rows, (end_tile - first_tile) * source_cols,
                                 source_rows)),
                   target, target.size(), 0, 0, cv::INTER_LINEAR);
        resized_ = resized_.empty() ? tiles : (resized_ | tiles);
      }
    }
  }
  if (recalled == nullptr && new_background) conversions.add(bgr, hsv_, small_hsv_);
  const double scale_x = static_cast<double>(bgr.cols) / kZoneSegmentationWidthPx;
  const double scale_y = static_cast<double>(bgr.rows) / small_height;
  ++counters_.images;

  // The masks change only where the downsampled image did.
  const cv::Rect small_whole(cv::Point(0, 0), small_size);
  cv::Rect region = small_whole;
  if (previous_small_.size() == small_size && rasters_[0]->mask().size() == small_size) {
    // Outside the tiles resized just now the two are equal.
    region = cv::Rect();
    if (!resized_.empty()) {
      const cv::Rect differing = differing_rect(small_hsv_(resized_), previous_small_(resized_));
      if (!differing.empty()) region = differing + resized_.tl();
    }
  } else {
    for (auto& raster : rasters_) raster->resize(small_size);
  }
  const auto mask_changes = update_masks(region);
  // A new background: the masks its thread saw recently are not segmented again.
  const bool whole_new = region.area() * 2 >= small_whole.area();
  thread_local MaskMemo memo;

  ZoneMap map;
  for (std::size_t c = 0; c < kRanges.size(); ++c) {
    auto& raster = *rasters_[c];
    if (mask_changes[c].empty()) {
      ++counters_.masks_reused;
    } else if (!whole_new) {
      ++counters_.masks_recomputed;
      raster.update(mask_changes[c], counters_);
    } else {
      const std::uint64_t hash = hash_of(raster.mask());
      if (const auto* known = memo.find(hash, raster.mask())) {
        ++counters_.masks_reused;
        raster.adopt(*known);
      } else {
        ++counters_.masks_recomputed;
        raster.update(small_whole, counters_);
        memo.add(hash, raster.mask(), raster.contours());
      }
    }
    map.add_zones(kRanges[c].colour, raster.contours(), scale_x, scale_y, metres_per_pixel);
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
