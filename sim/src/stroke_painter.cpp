#include "freeplay/sim/stroke_painter.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <cmath>
#include <limits>

#include <opencv2/core/hal/intrin.hpp>

#include "freeplay/core/error.hpp"

namespace freeplay::sim {
namespace {

// One segment a–b of a polyline with what every row and pixel test needs of it.
struct Segment {
  cv::Point2d a, b, ab;
  double length = 0.0;
  double length2 = 0.0;
  cv::Point2d u, n;  // unit direction and normal (zero for a dot)
  double inv_ux = 0.0, inv_nx = 0.0;  // 1 / u.x and 1 / n.x (0 where that component is below 1e-12)
  bool end_cap = true;  // whether b's disc belongs to the rows' intervals (see StrokePainter::cover)

  Segment(const cv::Point2d& from, const cv::Point2d& to, bool with_end_cap)
      : a(from), b(to), ab(to - from), end_cap(with_end_cap) {
    length2 = ab.dot(ab);
    length = std::sqrt(length2);
    if (length > 0.0) {
      u = ab / length;
      n = {-u.y, u.x};
      if (std::abs(u.x) >= 1e-12) inv_ux = 1.0 / u.x;
      if (std::abs(n.x) >= 1e-12) inv_nx = 1.0 / n.x;
    }
  }

  // The x-intervals of a row within distance `outer` and within distance `inner` (< outer) of the segment (a
  // capsule: convex, so the hull of what its two discs and its rectangle cut from the row); both intervals share
  // the row's offsets and the clip along the segment, which do not depend on the distance.
  // The ends need not be exact to the last bit: a pixel centre within 1e-9 px of an end is at distance ≈ inner
  // (coverage 255 whether filled or measured), ≈ outer (coverage 0 whether in the row's run or not), or on the cut
  // through b of a segment without its end disc (the next segment's disc at b gives it at least as much), so the
  // clips multiply by the slope's reciprocal instead of dividing by it.
  // Lane i is row y + i: [lo, hi] (none when lo > hi) and [in_lo, in_hi] (likewise). Kept as written by whole
  // SIMD stores and read one double at a time (a copy of a freshly stored mixed struct would stall).
  struct RowPair {
    alignas(16) std::array<double, 2> lo, hi, in_lo, in_hi;
  };
  // Rows `y` and `y` + 1 at once, two lanes of SIMD doubles (the same operations as one row at a time, lane by
  // lane: a row beyond a disc or a clip is masked out instead of skipped).
  void row_intervals(double y, double outer, double inner, RowPair& out) const {
    using V = cv::v_float64x2;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const V inf = cv::v_setall_f64(kInf);
    const V minus_inf = cv::v_setall_f64(-kInf);
    const V zero = cv::v_setzero_f64();
    const V ys(y, y + 1.0);
    V lo = inf, hi = minus_inf, in_lo = inf, in_hi = minus_inf;
    const bool with_inner = inner > 0.0;
    const V v_outer = cv::v_setall_f64(outer);
    const V v_inner = cv::v_setall_f64(inner);
    for (const cv::Point2d* c : {&a, &b}) {
      if (c == &b && !end_cap) break;
      const V dy = ys - cv::v_setall_f64(c->y);
      const V ady = cv::v_abs(dy);
      const V dy2 = dy * dy;
      const V cx = cv::v_setall_f64(c->x);
      const V in_disc = ady <= v_outer;
      const V h = cv::v_sqrt(cv::v_max(cv::v_setall_f64(outer * outer) - dy2, zero));
      lo = cv::v_select(in_disc, cv::v_min(lo, cx - h), lo);
      hi = cv::v_select(in_disc, cv::v_max(hi, cx + h), hi);
      if (!with_inner) continue;
      const V in_core = ady <= v_inner;
      const V h_in = cv::v_sqrt(cv::v_max(cv::v_setall_f64(inner * inner) - dy2, zero));
      in_lo = cv::v_select(in_core, cv::v_min(in_lo, cx - h_in), in_lo);
      in_hi = cv::v_select(in_core, cv::v_max(in_hi, cx + h_in), in_hi);
    }
    if (length > 0.0) {
      // Along the segment 0 ≤ (p − a)·u ≤ length and across it |(p − a)·n| ≤ t, each linear in x along the row.
      // `inverse` is 1 / slope, or 0 for a slope below 1e-12 (the row's offset is then constant along it).
      const auto clip = [](V& from, V& to, double inverse, const V& offset, double low, double high) {
        const V v_low = cv::v_setall_f64(low);
        const V v_high = cv::v_setall_f64(high);
        if (inverse == 0.0) {
          const V empty = (offset < v_low) | (offset > v_high);
          from = cv::v_select(empty, to + cv::v_setall_f64(1.0), from);
          return;
        }
        const V e0 = (v_low - offset) * cv::v_setall_f64(inverse);
        const V e1 = (v_high - offset) * cv::v_setall_f64(inverse);
        from = cv::v_max(from, cv::v_min(e0, e1));
        to = cv::v_min(to, cv::v_max(e0, e1));
      };
      V x0 = minus_inf;
      V x1 = inf;
      const V dy = ys - cv::v_setall_f64(a.y);
      clip(x0, x1, inv_ux, cv::v_setall_f64(-a.x * u.x) + dy * cv::v_setall_f64(u.y), 0.0, length);
      const V across = cv::v_setall_f64(-a.x * n.x) + dy * cv::v_setall_f64(n.y);
      V in_x0 = x0;
      V in_x1 = x1;
      clip(x0, x1, inv_nx, across, -outer, outer);
      const V met = x0 <= x1;
      lo = cv::v_select(met, cv::v_min(lo, x0), lo);
      hi = cv::v_select(met, cv::v_max(hi, x1), hi);
      if (with_inner) {
        clip(in_x0, in_x1, inv_nx, across, -inner, inner);
        const V met_inner = met & (in_x0 <= in_x1);
        in_lo = cv::v_select(met_inner, cv::v_min(in_lo, in_x0), in_lo);
        in_hi = cv::v_select(met_inner, cv::v_max(in_hi, in_x1), in_hi);
      }
    }
    cv::v_store_aligned(out.lo.data(), lo);
    cv::v_store_aligned(out.hi.data(), hi);
    cv::v_store_aligned(out.in_lo.data(), in_lo);
    cv::v_store_aligned(out.in_hi.data(), in_hi);
  }

  // Distance from `p` to the segment.
  double distance(double px, double py) const {
    const double dx = px - a.x;
    const double dy = py - a.y;
    const double s = length2 > 0.0 ? std::clamp((dx * ab.x + dy * ab.y) / length2, 0.0, 1.0) : 0.0;
    const double ex = dx - s * ab.x;
    const double ey = dy - s * ab.y;
    return std::sqrt(ex * ex + ey * ey);
  }
};

// ⌈v⌉ and ⌊v⌋ as int for a finite v within int's range (a row interval's ends), as static_cast<int>(std::ceil(v))
// gives them, without the rounding-mode sequence baseline x86-64 inlines for std::ceil.
int ceil_to_int(double v) {
  const int truncated = static_cast<int>(v);
  return truncated + (static_cast<double>(truncated) < v ? 1 : 0);
}

int floor_to_int(double v) {
  const int truncated = static_cast<int>(v);
  return truncated - (static_cast<double>(truncated) > v ? 1 : 0);
}

}  // namespace

void StrokePainter::cover(const std::vector<cv::Point2d>& path, double width_px, int cols, int rows) {
  const auto size = static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows);
  if (coverage_.size() < size) coverage_.resize(size, 0);
  span_lo_.assign(static_cast<std::size_t>(rows), cols);
  span_hi_.assign(static_cast<std::size_t>(rows), -1);
  runs_.clear();
  const double outer = 0.5 * width_px + 0.5;  // coverage > 0 below this distance
  const double inner = 0.5 * width_px - 0.5;  // coverage 1 up to this distance
  const std::size_t segments = path.size() > 1 ? path.size() - 1 : 1;
  // A pixel whose nearest point on segment k is its end b is at least as near segment k + 1, which starts at b, so
  // segment k's coverage there never wins: only the last segment's rows take in the disc around its end.
  const auto segment_at = [&path, segments](std::size_t k) {
    return Segment(path[k], path[std::min(k + 1, path.size() - 1)], k + 1 == segments);
  };
  // Each pixel ends with the largest coverage any segment gives it, so the order of the writes does not matter:
  // every segment's fully covered run is filled first, and then a rim pixel that a later segment covers fully
  // needs no distance.
  for (std::size_t k = 0; k < segments; ++k) {
    const Segment segment = segment_at(k);
    double top = std::min(segment.a.y, segment.b.y) - outer;
    double bottom = std::max(segment.a.y, segment.b.y) + outer;
    if (!segment.end_cap) {
      // The rows of a's disc and of the rectangle (its corners are a ± outer·n and b ± outer·n, n.y = u.x), with a
      // hair of margin: a row beyond them meets the shape at most in a point, where the coverage is 0.
      const double half = outer * std::abs(segment.u.x) + 1e-9;
      top = std::max(top, std::min(segment.a.y - outer, std::min(segment.a.y, segment.b.y) - half));
      bottom = std::min(bottom, std::max(segment.a.y + outer, std::max(segment.a.y, segment.b.y) + half));
    }
    const int y0 = std::max(0, static_cast<int>(std::ceil(top)));
    const int y1 = std::min(rows - 1, static_cast<int>(std::floor(bottom)));
    Segment::RowPair pair;
    for (int y = y0; y <= y1; ++y) {
      const auto lane = static_cast<std::size_t>((y - y0) % 2);
      if (lane == 0) segment.row_intervals(y, outer, inner, pair);
      const double lo = pair.lo[lane];
      const double hi = pair.hi[lane];
      if (!(lo <= hi)) continue;  // the row misses the capsule
      const int x0 = std::max(0, ceil_to_int(lo));
      const int x1 = std::min(cols - 1, floor_to_int(hi));
      if (x0 > x1) continue;
      // Fully covered pixels [f0, f1] (none when f0 > f1); the rest of [x0, x1] is the anti-aliased rim.
      int f0 = x1 + 1;
      int f1 = x1;
      if (pair.in_lo[lane] <= pair.in_hi[lane]) {  // the row meets the fully covered core
        f0 = std::max(x0, ceil_to_int(pair.in_lo[lane]));
        f1 = std::min(x1, floor_to_int(pair.in_hi[lane]));
        if (f0 > f1) f0 = x1 + 1, f1 = x1;
      }
      std::uint8_t* row = coverage_.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(cols);
      if (f0 <= f1) std::fill(row + f0, row + f1 + 1, std::uint8_t{255});
      span_lo_[static_cast<std::size_t>(y)] = std::min(span_lo_[static_cast<std::size_t>(y)], x0);
      span_hi_[static_cast<std::size_t>(y)] = std::max(span_hi_[static_cast<std::size_t>(y)], x1);
      // Written field by field where it is kept: a run built aside and copied in would be read back with wider
      // loads than it was stored with, which stalls the store forwarding once per row.
      RowRun& run = runs_.emplace_back();
      run.segment = k;
      run.y = y;
      run.x0 = x0;
      run.x1 = x1;
      run.f0 = f0;
      run.f1 = f1;
    }
  }
  std::size_t current = segments;
  Segment segment = segment_at(0);
  for (const RowRun& run : runs_) {
    if (run.segment != current) segment = segment_at(current = run.segment);
    std::uint8_t* row = coverage_.data() + static_cast<std::size_t>(run.y) * static_cast<std::size_t>(cols);
    const auto rim = [&](int from, int to) {
      for (int x = from; x <= to; ++x) {
        if (row[x] == 255) continue;  // nothing can add to full coverage
        const double a = std::clamp(outer - segment.distance(x, run.y), 0.0, 1.0);
        row[x] = std::max(row[x], static_cast<std::uint8_t>(255.0 * a + 0.5));
      }
    };
    if (run.f0 <= run.f1) {
      rim(run.x0, run.f0 - 1);
      rim(run.f1 + 1, run.x1);
    } else {
      rim(run.x0, run.x1);
    }
  }
}

template <typename SourceOf>
void StrokePainter::blend(cv::Mat& target, const std::vector<cv::Point2d>& path, double width_px,
                          const SourceOf& source_of) {
  if (target.type() != CV_8UC3) throw InputError("strokes are painted into BGR images", "target", "CV_8UC3");
  if (path.empty()) return;
  cover(path, width_px, target.cols, target.rows);
  for (int y = 0; y < target.rows; ++y) {
    const int lo = span_lo_[static_cast<std::size_t>(y)];
    const int hi = span_hi_[static_cast<std::size_t>(y)];
    std::uint8_t* row = coverage_.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(target.cols);
    auto* pixels = target.ptr<cv::Vec3b>(y);
    for (int x = lo; x <= hi; ++x) {
      const int a = row[x];
      if (a == 0) continue;
      if (a == 255) {
        // A run of full coverage takes the source as it is.
        int end = x + 1;
        while (end <= hi && row[end] == 255) ++end;
        std::memset(row + x, 0, static_cast<std::size_t>(end - x));  // the buffer is all 0 again after the call
        source_of.copy_run(y, x, end - x, pixels + x);
        x = end - 1;
        continue;
      }
      row[x] = 0;
      const cv::Vec3b source = source_of(y, x);
      for (int c = 0; c < 3; ++c) {
        pixels[x][c] = static_cast<std::uint8_t>((pixels[x][c] * (255 - a) + source[c] * a + 127) / 255);
      }
    }
  }
}

namespace {

// One colour everywhere (painting).
class ColourSource {
 public:
  explicit ColourSource(const cv::Vec3b& bgr) : bgr_(bgr) {
    for (std::size_t i = 0; i < kPatternPixels; ++i) std::memcpy(pattern_.data() + 3 * i, bgr.val, 3);
  }
  cv::Vec3b operator()(int /*y*/, int /*x*/) const { return bgr_; }
  // Writes the colour into `count` pixels from `out`.
  void copy_run(int /*y*/, int /*x*/, int count, cv::Vec3b* out) const {
    auto* bytes = reinterpret_cast<std::uint8_t*>(out);
    auto left = static_cast<std::size_t>(count);
    for (; left >= kPatternPixels; left -= kPatternPixels, bytes += pattern_.size()) {
      std::memcpy(bytes, pattern_.data(), pattern_.size());
    }
    std::memcpy(bytes, pattern_.data(), 3 * left);
  }

 private:
  static constexpr std::size_t kPatternPixels = 16;
  cv::Vec3b bgr_;
  std::array<std::uint8_t, 3 * kPatternPixels> pattern_{};
};

// Each pixel of a BGR image (erasing back to the background).
class ImageSource {
 public:
  explicit ImageSource(const cv::Mat& image) : image_(image) {}
  cv::Vec3b operator()(int y, int x) const { return image_.at<cv::Vec3b>(y, x); }
  // Copies the image's pixels (y, x) … (y, x + count − 1) to `out`.
  void copy_run(int y, int x, int count, cv::Vec3b* out) const {
    std::memcpy(static_cast<void*>(out), image_.ptr<cv::Vec3b>(y) + x, 3 * static_cast<std::size_t>(count));
  }

 private:
  const cv::Mat& image_;
};

}  // namespace

void StrokePainter::paint(cv::Mat& target, const std::vector<cv::Point2d>& path, double width_px, const cv::Vec3b& bgr) {
  blend(target, path, width_px, ColourSource(bgr));
}

void StrokePainter::erase(cv::Mat& target, const cv::Mat& background, const std::vector<cv::Point2d>& path,
                          double width_px) {
  if (background.type() != CV_8UC3 || background.size() != target.size()) {
    throw InputError("erasing needs a BGR background of the target's size", "background", "CV_8UC3, same size");
  }
  blend(target, path, width_px, ImageSource(background));
}

}  // namespace freeplay::sim
