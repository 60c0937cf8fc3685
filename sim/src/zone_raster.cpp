// Incremental zone rasters. Why a windowed update gives OpenCV's whole-image result:
// - Erosion and dilation by a rectangle read a fixed neighbourhood, so a mask change inside C changes the opened and
//   dilated mask only inside C grown by 5 pixels (2 + 2 + 1), and those pixels are recomputed from the full mask.
// - OpenCV's two-pass 5×5 chamfer transform gives every pixel the cheapest move path to a zero pixel (moves of
//   1, 1.4 and 2.1969 in 16.16 fixed point). A pixel whose old distance is shorter than its distance to the changed
//   rectangle R keeps it (its nearest zero is outside R and no new zero in R is nearer); every move costs at least
//   1 per pixel of Chebyshev distance, so only pixels with distance ≥ 65536 × Chebyshev(p, R) can change. The two
//   passes are rerun on the bounding box W of those pixels with a 2-pixel ring of unchanged distances around it
//   (moves are at most 2 pixels long, so every path leaving W crosses the ring).
// - The threshold depends on the maximum distance: if it moved, the whole foreground is recomputed; contours are
//   searched again (whole image, as the real node does) only when the foreground changed.

#include "freeplay/sim/zone_raster.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace freeplay::sim::detail {
namespace {

// OpenCV's DIST_L2 / DIST_MASK_5 weights (1, 1.4, 2.1969) rounded to 16.16 fixed point as its transform does.
constexpr std::uint32_t kStraight = 65536;
constexpr std::uint32_t kDiagonal = 91750;
constexpr std::uint32_t kKnight = 143976;
constexpr float kFixedToPixels = 1.0F / 65536.0F;
constexpr std::uint32_t kFar = 1U << 30;  // "no zero reached yet": above any distance in an image of ≤ 16384 px
constexpr int kRing = 2;                  // longest move of the 5×5 mask

cv::Rect grown(const cv::Rect& r, int by, const cv::Size& size) {
  return cv::Rect(r.x - by, r.y - by, r.width + 2 * by, r.height + 2 * by) & cv::Rect(cv::Point(0, 0), size);
}

/// dst = minimum (kMin) or maximum of src over the (2r+1)² square clipped to the image, for the pixels of `region`
/// (OpenCV's erode / dilate with a rectangle and its default border, which never wins). Separable, with the pixels
/// outside the image set to the neutral value so that the inner loops have a fixed length (`r` fixed: unrolled).
template <bool kMin, int r>
void square_filter(const cv::Mat& src, cv::Mat& dst, const cv::Rect& region, std::vector<unsigned char>& rows) {
  constexpr unsigned char kNeutral = kMin ? 255 : 0;
  const auto pick = [](unsigned char a, unsigned char b) { return kMin ? std::min(a, b) : std::max(a, b); };
#if CV_SIMD128
  const auto pick16 = [](const cv::v_uint8x16& a, const cv::v_uint8x16& b) {
    return kMin ? cv::v_min(a, b) : cv::v_max(a, b);
  };
#endif
  const int w = region.width;
  const int h = region.height + 2 * r;
  const int line_width = w + 2 * r;
  rows.resize(static_cast<std::size_t>(h * w + line_width));
  unsigned char* line = rows.data() + static_cast<std::ptrdiff_t>(h) * w;
  const int x_first = std::max(0, region.x - r);
  const int x_end = std::min(src.cols, region.x + w + r);
  for (int i = 0; i < h; ++i) {
    unsigned char* out = rows.data() + static_cast<std::ptrdiff_t>(i) * w;
    const int y = region.y - r + i;
    if (y < 0 || y >= src.rows) {
      std::memset(out, kNeutral, static_cast<std::size_t>(w));
      continue;
    }
    std::memset(line, kNeutral, static_cast<std::size_t>(line_width));
    std::memcpy(line + (x_first - (region.x - r)), src.ptr<unsigned char>(y) + x_first,
                static_cast<std::size_t>(x_end - x_first));
    int x = 0;
#if CV_SIMD128
    for (; x + 16 <= w; x += 16) {  // sixteen pixels at a time with OpenCV's universal intrinsics
      cv::v_uint8x16 v = cv::v_load(line + x);
      for (int k = 1; k <= 2 * r; ++k) v = pick16(v, cv::v_load(line + x + k));
      cv::v_store(out + x, v);
    }
#endif
    for (; x < w; ++x) {
      unsigned char v = line[x];
      for (int k = 1; k <= 2 * r; ++k) v = pick(v, line[x + k]);
      out[x] = v;
    }
  }
  for (int i = 0; i < region.height; ++i) {
    unsigned char* d = dst.ptr<unsigned char>(region.y + i) + region.x;
    const unsigned char* first = rows.data() + static_cast<std::ptrdiff_t>(i) * w;
    int x = 0;
#if CV_SIMD128
    for (; x + 16 <= w; x += 16) {
      cv::v_uint8x16 v = cv::v_load(first + x);
      for (int k = 1; k <= 2 * r; ++k) v = pick16(v, cv::v_load(first + static_cast<std::ptrdiff_t>(k) * w + x));
      cv::v_store(d + x, v);
    }
#endif
    for (; x < w; ++x) {
      unsigned char v = first[x];
      for (int k = 1; k <= 2 * r; ++k) v = pick(v, first[static_cast<std::ptrdiff_t>(k) * w + x]);
      d[x] = v;
    }
  }
}

/// The two chamfer passes over `window` of `binary`: zero pixels get 0, the others the cheapest path to a zero pixel
/// or to a ring pixel (outside the window: its value in `distance`, or kFar outside the image). Writes `distance`
/// inside the window only.
void chamfer_window(const cv::Mat& binary, std::vector<std::uint32_t>& distance, const cv::Rect& window,
                    std::vector<std::uint32_t>& buffer) {
  const int ww = window.width + 2 * kRing;
  const int wh = window.height + 2 * kRing;
  buffer.resize(static_cast<std::size_t>(ww * wh));
  const int cols = binary.cols;
  // Columns of the buffer inside the image: [inside_from, inside_end); the window's own are [kRing, ww - kRing).
  const int inside_from = std::max(0, -(window.x - kRing));
  const int inside_end = std::min(ww, cols - (window.x - kRing));
  for (int by = 0; by < wh; ++by) {
    const int y = window.y - kRing + by;
    std::uint32_t* b = buffer.data() + static_cast<std::ptrdiff_t>(by) * ww;
    if (y < 0 || y >= binary.rows) {
      std::fill(b, b + ww, kFar);
      continue;
    }
    std::fill(b, b + inside_from, kFar);
    std::fill(b + inside_end, b + ww, kFar);
    // known(bx): the distance already known at buffer column bx of this row (bx inside the image).
    const std::uint32_t* row = distance.data() + static_cast<std::ptrdiff_t>(y) * cols;
    const auto known = [row, &window](int bx) { return row + (window.x - kRing + bx); };
    if (y < window.y || y >= window.y + window.height) {
      std::copy(known(inside_from), known(inside_end), b + inside_from);  // a ring row
      continue;
    }
    std::copy(known(inside_from), known(std::max(inside_from, kRing)), b + inside_from);  // the ring left and right
    std::copy(known(std::min(inside_end, ww - kRing)), known(inside_end), b + std::min(inside_end, ww - kRing));
    const unsigned char* pixels = binary.ptr<unsigned char>(y) + window.x;
    for (int x = 0; x < window.width; ++x) b[kRing + x] = pixels[x] == 0 ? 0 : kFar;
  }
  const std::ptrdiff_t s = ww;
  for (int by = kRing; by < wh - kRing; ++by) {
    std::uint32_t* t = buffer.data() + by * s;
    for (int bx = kRing; bx < ww - kRing; ++bx) {
      if (t[bx] == 0) continue;
      std::uint32_t v = t[bx - 2 * s - 1] + kKnight;
      v = std::min(v, t[bx - 2 * s + 1] + kKnight);
      v = std::min(v, t[bx - s - 2] + kKnight);
      v = std::min(v, t[bx - s - 1] + kDiagonal);
      v = std::min(v, t[bx - s] + kStraight);
      v = std::min(v, t[bx - s + 1] + kDiagonal);
      v = std::min(v, t[bx - s + 2] + kKnight);
      v = std::min(v, t[bx - 1] + kStraight);
      t[bx] = v;
    }
  }
  for (int by = wh - kRing - 1; by >= kRing; --by) {
    std::uint32_t* t = buffer.data() + by * s;
    for (int bx = ww - kRing - 1; bx >= kRing; --bx) {
      std::uint32_t v = t[bx];
      if (v > kStraight) {
        v = std::min(v, t[bx + 2 * s + 1] + kKnight);
        v = std::min(v, t[bx + 2 * s - 1] + kKnight);
        v = std::min(v, t[bx + s + 2] + kKnight);
        v = std::min(v, t[bx + s + 1] + kDiagonal);
        v = std::min(v, t[bx + s] + kStraight);
        v = std::min(v, t[bx + s - 1] + kDiagonal);
        v = std::min(v, t[bx + s - 2] + kKnight);
        v = std::min(v, t[bx + 1] + kStraight);
        t[bx] = v;
      }
    }
  }
  for (int y = window.y; y < window.y + window.height; ++y) {
    const std::uint32_t* b = buffer.data() + static_cast<std::ptrdiff_t>(y - window.y + kRing) * ww + kRing;
    std::copy_n(b, window.width, distance.data() + static_cast<std::ptrdiff_t>(y) * cols + window.x);
  }
}

static_assert(std::endian::native == std::endian::little, "the byte scans read the lowest address as the lowest byte");

/// Index of the first non-zero byte of row[0, n), or n; eight bytes at a time.
int first_non_zero(const unsigned char* row, int n) {
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    std::uint64_t word;
    std::memcpy(&word, row + x, 8);
    if (word != 0) return x + std::countr_zero(word) / 8;  // little-endian: the lowest byte comes first
  }
  for (; x < n; ++x) {
    if (row[x] != 0) return x;
  }
  return n;
}

/// Index of the last non-zero byte of row[0, n) (the row has one); eight bytes at a time.
int last_non_zero(const unsigned char* row, int n) {
  int end = n;
  for (; end >= 8; end -= 8) {
    std::uint64_t word;
    std::memcpy(&word, row + end - 8, 8);
    if (word != 0) return end - 1 - std::countl_zero(word) / 8;
  }
  for (; end > 0; --end) {
    if (row[end - 1] != 0) return end - 1;
  }
  return -1;
}

}  // namespace

Contours reference_contours(const cv::Mat& colour_mask) {
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
  Contours contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(foreground, contours, hierarchy, cv::RETR_TREE, cv::CHAIN_APPROX_TC89_KCOS);
  return contours;
}

std::vector<std::uint32_t> chamfer_distances(const cv::Mat& binary) {
  std::vector<std::uint32_t> distance(binary.total(), kFar);
  std::vector<std::uint32_t> buffer;
  chamfer_window(binary, distance, cv::Rect(0, 0, binary.cols, binary.rows), buffer);
  return distance;
}

void ColourRaster::resize(cv::Size size) {
  mask_ = cv::Mat::zeros(size, CV_8UC1);
  for (cv::Mat* m : {&eroded_, &opened_, &next_, &dilated_, &core_, &foreground_}) m->create(size, CV_8UC1);
  distance_.assign(static_cast<std::size_t>(size.area()), kFar);
  valid_ = false;
  distance_valid_ = false;
  contours_.clear();
}

void ColourRaster::adopt(const Contours& contours) {
  contours_ = contours;
  valid_ = false;
  distance_valid_ = false;
}

void ColourRaster::update(const cv::Rect& changed_in, ColourRasterWork& work) {
  const cv::Size size = mask_.size();
  const cv::Rect changed = changed_in & cv::Rect(cv::Point(0, 0), size);
  if (changed.empty()) return;
  if (!valid_) {
    recompute_all(work);
    return;
  }
  // The opened and dilated mask, only where the change reaches; then what really changed.
  square_filter<true, 2>(mask_, eroded_, grown(changed, 8, size), scratch_);
  square_filter<false, 2>(eroded_, opened_, grown(changed, 6, size), scratch_);
  const cv::Rect reach = grown(changed, 5, size);
  square_filter<false, 1>(opened_, next_, reach, scratch_);
  int x0 = size.width, y0 = size.height, x1 = -1, y1 = -1;
  for (int y = reach.y; y < reach.y + reach.height; ++y) {
    unsigned char* d = dilated_.ptr<unsigned char>(y);
    const unsigned char* n = next_.ptr<unsigned char>(y);
    for (int x = reach.x; x < reach.x + reach.width; ++x) {
      if (d[x] == n[x]) continue;
      nonzero_ += n[x] != 0 ? 1 : -1;
      d[x] = n[x];
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return;  // the change vanished in the opening
  if (nonzero_ == 0 || nonzero_ == static_cast<int>(mask_.total()) || !distance_valid_) {
    recompute_all(work);
    return;
  }
  ++work.rasters_windowed;
  const std::uint32_t old_max = max_distance_;
  const cv::Rect window = update_distances(cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1), work);
  if (refresh_foreground(max_distance_ == old_max ? window : cv::Rect(cv::Point(0, 0), size))) find_contours(work);
}

void ColourRaster::recompute_all(ColourRasterWork& work) {
  ++work.rasters_full;
  const cv::Rect whole(cv::Point(0, 0), mask_.size());
  square_filter<true, 2>(mask_, eroded_, whole, scratch_);
  square_filter<false, 2>(eroded_, opened_, whole, scratch_);
  square_filter<false, 1>(opened_, dilated_, whole, scratch_);
  nonzero_ = cv::countNonZero(dilated_);
  valid_ = true;
  distance_valid_ = false;
  if (nonzero_ == 0) {
    core_.setTo(0);
    foreground_.setTo(0);
    contours_.clear();
    return;
  }
  if (nonzero_ == static_cast<int>(mask_.total())) {
    // No zero pixel: OpenCV's distances then grow from its far border value; let OpenCV do it.
    contours_ = reference_contours(mask_);
    core_.setTo(0);
    foreground_.setTo(0);
    return;
  }
  chamfer_window(dilated_, distance_, whole, window_);
  work.distance_pixels += static_cast<std::uint64_t>(whole.area());
  refresh_row_maxima(0, whole.height);
  distance_valid_ = true;
  refresh_foreground(whole);
  find_contours(work);
}

cv::Rect ColourRaster::update_distances(const cv::Rect& moved, ColourRasterWork& work) {
  const cv::Size size = mask_.size();
  const cv::Rect scan = grown(moved, static_cast<int>(max_distance_ / kStraight), size);
  int x0 = moved.x, y0 = moved.y, x1 = moved.x + moved.width - 1, y1 = moved.y + moved.height - 1;
  for (int y = scan.y; y < scan.y + scan.height; ++y) {
    // No pixel of a row whose largest distance is below 65536 × its Chebyshev distance to `moved` can change.
    const auto row_max = static_cast<std::uint64_t>(row_max_[static_cast<std::size_t>(y)]);
    const int dy = y < moved.y ? moved.y - y : std::max(0, y - (moved.y + moved.height - 1));
    if (row_max < static_cast<std::uint64_t>(dy) * kStraight) continue;
    const int row_reach = static_cast<int>(row_max / kStraight);
    const int xa = std::max(scan.x, moved.x - row_reach);
    const int xb = std::min(scan.x + scan.width, moved.x + moved.width + row_reach);
    const std::uint32_t* d = distance_.data() + static_cast<std::ptrdiff_t>(y) * size.width;
    for (int x = xa; x < xb; ++x) {
      const int dx = x < moved.x ? moved.x - x : std::max(0, x - (moved.x + moved.width - 1));
      const auto chebyshev = static_cast<std::uint64_t>(std::max(dx, dy));
      if (static_cast<std::uint64_t>(d[x]) >= chebyshev * kStraight) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
    }
  }
  const cv::Rect window(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
  chamfer_window(dilated_, distance_, window, window_);
  work.distance_pixels += static_cast<std::uint64_t>(window.area());
  refresh_row_maxima(window.y, window.y + window.height);
  return window;
}

void ColourRaster::refresh_row_maxima(int first_row, int end_row) {
  const int cols = mask_.cols;
  row_max_.resize(static_cast<std::size_t>(mask_.rows));
  for (int y = first_row; y < end_row; ++y) {
    const std::uint32_t* d = distance_.data() + static_cast<std::ptrdiff_t>(y) * cols;
    std::uint32_t largest = 0;
    int x = 0;
#if CV_SIMD128
    if (cols >= 4) {  // four distances at a time
      cv::v_uint32x4 v = cv::v_load(d);
      for (x = 4; x + 4 <= cols; x += 4) v = cv::v_max(v, cv::v_load(d + x));
      largest = cv::v_reduce_max(v);
    }
#endif
    for (; x < cols; ++x) largest = std::max(largest, d[x]);
    row_max_[static_cast<std::size_t>(y)] = largest;
  }
  max_distance_ = *std::max_element(row_max_.begin(), row_max_.end());
}

bool ColourRaster::refresh_foreground(const cv::Rect& window) {
  const cv::Size size = mask_.size();
  // The real node's threshold: float distance > 0.25 × maximum (both exact in float at these magnitudes). The
  // float of a distance grows with it, so the test is distance ≥ the first value that passes.
  const float quarter = static_cast<float>(0.25 * static_cast<double>(static_cast<float>(max_distance_) * kFixedToPixels));
  const auto passes = [quarter](std::uint32_t t) { return static_cast<float>(t) * kFixedToPixels > quarter; };
  std::uint32_t first = max_distance_ / 4;
  while (first > 0 && passes(first - 1)) --first;
  while (!passes(first)) ++first;
  for (int y = window.y; y < window.y + window.height; ++y) {
    unsigned char* c = core_.ptr<unsigned char>(y);
    const std::uint32_t* d = distance_.data() + static_cast<std::ptrdiff_t>(y) * size.width;
    int x = window.x;
#if CV_SIMD128
    // Sixteen at a time: each comparison is all ones or zero, and the saturating packs keep that as 255 or 0.
    const cv::v_uint32x4 threshold = cv::v_setall_u32(first);
    for (; x + 16 <= window.x + window.width; x += 16) {
      const cv::v_uint16x8 low = cv::v_pack(cv::v_load(d + x) >= threshold, cv::v_load(d + x + 4) >= threshold);
      const cv::v_uint16x8 high = cv::v_pack(cv::v_load(d + x + 8) >= threshold, cv::v_load(d + x + 12) >= threshold);
      cv::v_store(c + x, cv::v_pack(low, high));
    }
#endif
    for (; x < window.x + window.width; ++x) c[x] = d[x] >= first ? 255 : 0;
  }
  const cv::Rect out = grown(window, 2, size);
  square_filter<false, 2>(core_, next_, out, scratch_);
  bool changed = false;
  for (int y = out.y; y < out.y + out.height; ++y) {
    unsigned char* f = foreground_.ptr<unsigned char>(y) + out.x;
    const unsigned char* n = next_.ptr<unsigned char>(y) + out.x;
    if (std::memcmp(f, n, static_cast<std::size_t>(out.width)) != 0) {
      changed = true;
      std::memcpy(f, n, static_cast<std::size_t>(out.width));
    }
  }
  return changed;
}

void contours_of(const cv::Mat& binary, Contours& contours, std::vector<cv::Vec4i>& hierarchy) {
  // OpenCV pads the image it is given with zeros and scans it in raster order, so the box of the non-zero pixels,
  // shifted back, has the same contours in the same order as the whole image (all else there is zero).
  int top = -1;
  int bottom = -1;
  int left = binary.cols;
  int right = -1;
  for (int y = 0; y < binary.rows; ++y) {
    const unsigned char* row = binary.ptr<unsigned char>(y);
    const int first = first_non_zero(row, binary.cols);
    if (first == binary.cols) continue;
    if (top < 0) top = y;
    bottom = y;
    left = std::min(left, first);
    right = std::max(right, last_non_zero(row, binary.cols));
  }
  contours.clear();
  hierarchy.clear();
  if (top < 0) return;
  const cv::Rect box(left, top, right - left + 1, bottom - top + 1);
  cv::findContours(binary(box), contours, hierarchy, cv::RETR_TREE, cv::CHAIN_APPROX_TC89_KCOS, box.tl());
}

void ColourRaster::find_contours(ColourRasterWork& work) {
  ++work.contour_searches;
  contours_of(foreground_, contours_, hierarchy_);
}

}  // namespace freeplay::sim::detail
