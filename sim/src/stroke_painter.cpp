#include "freeplay/sim/stroke_painter.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <cmath>
#include <limits>

#include "freeplay/core/error.hpp"

namespace freeplay::sim {
namespace {

// One segment a–b of a polyline with what every row and pixel test needs of it.
struct Segment {
  cv::Point2d a, b, ab;
  double length = 0.0;
  double length2 = 0.0;
  cv::Point2d u, n;  // unit direction and normal (zero for a dot)
  bool end_cap = true;  // whether b's disc belongs to the rows' intervals (see StrokePainter::cover)

  Segment(const cv::Point2d& from, const cv::Point2d& to, bool with_end_cap)
      : a(from), b(to), ab(to - from), end_cap(with_end_cap) {
    length2 = ab.dot(ab);
    length = std::sqrt(length2);
    if (length > 0.0) {
      u = ab / length;
      n = {-u.y, u.x};
    }
  }

  // The x-intervals of row `y` within distance `outer` and within distance `inner` (< outer) of the segment (a
  // capsule: convex, so the hull of what its two discs and its rectangle cut from the row). `has_outer` is false
  // when the row misses the outer capsule, `has_inner` when it misses the inner one (or `inner` ≤ 0); both
  // intervals share the row's offsets and the clip along the segment, which do not depend on the distance.
  struct RowIntervals {
    double lo, hi, in_lo, in_hi;
    bool has_outer, has_inner;
  };
  RowIntervals row_intervals(double y, double outer, double inner) const {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    RowIntervals r{kInf, -kInf, kInf, -kInf, false, false};
    const bool with_inner = inner > 0.0;
    for (const cv::Point2d* c : {&a, &b}) {
      if (c == &b && !end_cap) break;
      const double dy = y - c->y;
      const double ady = std::abs(dy);
      if (ady > outer) continue;
      const double h = std::sqrt(outer * outer - dy * dy);
      r.lo = std::min(r.lo, c->x - h);
      r.hi = std::max(r.hi, c->x + h);
      if (!with_inner || ady > inner) continue;
      const double h_in = std::sqrt(inner * inner - dy * dy);
      r.in_lo = std::min(r.in_lo, c->x - h_in);
      r.in_hi = std::max(r.in_hi, c->x + h_in);
    }
    if (length > 0.0) {
      // Along the segment 0 ≤ (p − a)·u ≤ length and across it |(p − a)·n| ≤ t, each linear in x along the row.
      double x0 = -kInf;
      double x1 = kInf;
      const double dy = y - a.y;
      const auto clip = [](double& lo, double& hi, double slope, double offset, double low, double high) {
        if (std::abs(slope) < 1e-12) {
          if (offset < low || offset > high) lo = hi + 1.0;  // empty
          return;
        }
        double e0 = (low - offset) / slope;
        double e1 = (high - offset) / slope;
        if (e0 > e1) std::swap(e0, e1);
        lo = std::max(lo, e0);
        hi = std::min(hi, e1);
      };
      clip(x0, x1, u.x, -a.x * u.x + dy * u.y, 0.0, length);
      const double across = -a.x * n.x + dy * n.y;
      double in_x0 = x0;
      double in_x1 = x1;
      clip(x0, x1, n.x, across, -outer, outer);
      if (x0 <= x1) {
        r.lo = std::min(r.lo, x0);
        r.hi = std::max(r.hi, x1);
        if (with_inner) {
          clip(in_x0, in_x1, n.x, across, -inner, inner);
          if (in_x0 <= in_x1) {
            r.in_lo = std::min(r.in_lo, in_x0);
            r.in_hi = std::max(r.in_hi, in_x1);
          }
        }
      }
    }
    r.has_outer = r.lo <= r.hi;
    r.has_inner = r.in_lo <= r.in_hi;
    return r;
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
    for (int y = y0; y <= y1; ++y) {
      const auto spans = segment.row_intervals(y, outer, inner);
      if (!spans.has_outer) continue;
      RowRun run{k, y, std::max(0, ceil_to_int(spans.lo)), std::min(cols - 1, floor_to_int(spans.hi)), 0, 0};
      if (run.x0 > run.x1) continue;
      // Fully covered pixels [f0, f1] (none when f0 > f1); the rest of [x0, x1] is the anti-aliased rim.
      run.f0 = run.x1 + 1;
      run.f1 = run.x1;
      if (spans.has_inner) {
        run.f0 = std::max(run.x0, ceil_to_int(spans.in_lo));
        run.f1 = std::min(run.x1, floor_to_int(spans.in_hi));
        if (run.f0 > run.f1) run.f0 = run.x1 + 1, run.f1 = run.x1;
      }
      std::uint8_t* row = coverage_.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(cols);
      if (run.f0 <= run.f1) std::fill(row + run.f0, row + run.f1 + 1, std::uint8_t{255});
      span_lo_[static_cast<std::size_t>(y)] = std::min(span_lo_[static_cast<std::size_t>(y)], run.x0);
      span_hi_[static_cast<std::size_t>(y)] = std::max(span_hi_[static_cast<std::size_t>(y)], run.x1);
      runs_.push_back(run);
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
