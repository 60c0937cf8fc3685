// Our own item pictures: flat cartoon shapes drawn from primitives at any size (no sprites are copied).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <png.h>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/sim/screen_renderer.hpp"

namespace freeplay::sim {
namespace {

constexpr int kShiftBits = 4;
constexpr double kShiftScale = 1 << kShiftBits;

cv::Scalar rgb(int r, int g, int b) { return {static_cast<double>(b), static_cast<double>(g), static_cast<double>(r)}; }

/// Draws in a unit square (x right, y down, [0, 1]²) onto a colour layer and its alpha mask at once.
class Painter {
 public:
  explicit Painter(int side) : side_(side), bgr_(side, side, CV_8UC3, cv::Scalar(0, 0, 0)), alpha_(side, side, CV_8UC1, cv::Scalar(0)) {}

  void ellipse(double cx, double cy, double rx, double ry, const cv::Scalar& colour, double angle = 0.0) {
    each([&](cv::Mat& m, const cv::Scalar& c) {
      cv::ellipse(m, point(cx, cy), cv::Size(fixed(rx), fixed(ry)), angle, 0, 360, c, cv::FILLED, cv::LINE_AA, kShiftBits);
    }, colour);
  }
  void circle(double cx, double cy, double r, const cv::Scalar& colour) { ellipse(cx, cy, r, r, colour); }
  void polygon(const std::vector<cv::Point2d>& points, const cv::Scalar& colour) {
    const std::vector<std::vector<cv::Point>> polys = {to_points(points)};
    each([&](cv::Mat& m, const cv::Scalar& c) { cv::fillPoly(m, polys, c, cv::LINE_AA, kShiftBits); }, colour);
  }
  void line(const std::vector<cv::Point2d>& points, double width, const cv::Scalar& colour) {
    const std::vector<std::vector<cv::Point>> lines = {to_points(points)};
    const int thickness = std::max(1, static_cast<int>(std::lround(width * side_)));
    each([&](cv::Mat& m, const cv::Scalar& c) { cv::polylines(m, lines, false, c, thickness, cv::LINE_AA, kShiftBits); }, colour);
  }
  /// Runs `draw` and keeps only what falls inside the current opaque area (stripes, spots).
  void clipped(const std::function<void(Painter&)>& draw) {
    Painter layer(side_);
    draw(layer);
    cv::Mat mask;
    cv::min(layer.alpha_, alpha_, mask);
    layer.bgr_.copyTo(bgr_, mask);
  }
  /// Writes `text` centred at (cx, cy), at most `max_width` wide, dark with a light outline.
  void label(const std::string& text, double cx, double cy, double max_width) {
    const int font = cv::FONT_HERSHEY_SIMPLEX;
    int baseline = 0;
    const cv::Size unit = cv::getTextSize(text, font, 1.0, 1, &baseline);
    const double scale = std::min(max_width * side_ / unit.width, 0.11 * side_ / unit.height);
    const int thickness = std::max(1, static_cast<int>(std::lround(scale * 1.5)));
    const cv::Size size = cv::getTextSize(text, font, scale, thickness, &baseline);
    const cv::Point origin(static_cast<int>(cx * side_ - size.width / 2.0), static_cast<int>(cy * side_ + size.height / 2.0));
    const int outline = thickness + 2;
    cv::putText(bgr_, text, origin, font, scale, rgb(255, 255, 255), outline, cv::LINE_AA);
    cv::putText(alpha_, text, origin, font, scale, cv::Scalar(255), outline, cv::LINE_AA);
    cv::putText(bgr_, text, origin, font, scale, rgb(30, 30, 30), thickness, cv::LINE_AA);
  }
  cv::Mat bgra() const {
    cv::Mat out;
    std::vector<cv::Mat> channels;
    cv::split(bgr_, channels);
    channels.push_back(alpha_);
    cv::merge(channels, out);
    return out;
  }

 private:
  int fixed(double v) const { return static_cast<int>(std::lround(v * side_ * kShiftScale)); }
  cv::Point point(double x, double y) const { return {fixed(x), fixed(y)}; }
  std::vector<cv::Point> to_points(const std::vector<cv::Point2d>& points) const {
    std::vector<cv::Point> out;
    for (const auto& p : points) out.push_back(point(p.x, p.y));
    return out;
  }
  template <typename Draw>
  void each(Draw draw, const cv::Scalar& colour) {
    draw(bgr_, colour);
    draw(alpha_, cv::Scalar(255));
  }

  int side_;
  cv::Mat bgr_;
  cv::Mat alpha_;
};

cv::Scalar darker(const cv::Scalar& c, double f) { return c * f; }

void draw_zebra(Painter& p) {
  const cv::Scalar white = rgb(245, 245, 245), black = rgb(25, 25, 25);
  for (const double x : {0.3, 0.4, 0.6, 0.7}) p.line({{x, 0.55}, {x, 0.82}}, 0.06, white);
  p.line({{0.2, 0.5}, {0.1, 0.68}}, 0.025, black);  // tail
  p.ellipse(0.5, 0.52, 0.26, 0.15, white);
  p.line({{0.7, 0.47}, {0.8, 0.27}}, 0.12, white);  // neck
  p.ellipse(0.84, 0.26, 0.12, 0.07, white, 25);     // head
  p.clipped([&](Painter& s) {
    for (double x = 0.28; x < 0.95; x += 0.085) s.line({{x, 0.15}, {x - 0.06, 0.9}}, 0.03, black);
  });
  p.line({{0.66, 0.4}, {0.79, 0.18}}, 0.035, black);  // mane
  p.circle(0.87, 0.24, 0.018, black);                  // eye
  for (const double x : {0.3, 0.4, 0.6, 0.7}) p.line({{x, 0.82}, {x, 0.86}}, 0.06, black);  // hooves
}

void draw_elephant(Painter& p) {
  const cv::Scalar grey = rgb(150, 150, 165), dark = rgb(110, 110, 125);
  for (const double x : {0.28, 0.42, 0.58, 0.7}) p.line({{x, 0.6}, {x, 0.84}}, 0.1, grey);
  p.ellipse(0.48, 0.52, 0.3, 0.2, grey);
  p.line({{0.85, 0.5}, {0.9, 0.7}, {0.84, 0.84}}, 0.07, grey);  // trunk
  p.circle(0.78, 0.42, 0.15, grey);                              // head
  p.ellipse(0.68, 0.43, 0.09, 0.14, dark);                       // ear
  p.circle(0.84, 0.37, 0.022, rgb(20, 20, 20));                  // eye
  p.line({{0.86, 0.55}, {0.96, 0.52}}, 0.025, rgb(250, 250, 240));  // tusk
}

void draw_giraffe(Painter& p) {
  const cv::Scalar body = rgb(235, 185, 80), spot = rgb(150, 90, 30);
  for (const double x : {0.3, 0.4, 0.58, 0.66}) p.line({{x, 0.62}, {x, 0.92}}, 0.05, body);
  p.ellipse(0.48, 0.6, 0.22, 0.12, body);
  p.line({{0.62, 0.55}, {0.72, 0.15}}, 0.1, body);  // long neck
  p.ellipse(0.78, 0.12, 0.1, 0.06, body, 20);       // head
  p.clipped([&](Painter& s) {
    for (const auto& c : std::vector<cv::Point2d>{{0.35, 0.56}, {0.47, 0.62}, {0.58, 0.55}, {0.42, 0.68},
                                                  {0.66, 0.42}, {0.69, 0.28}, {0.3, 0.64}, {0.55, 0.68}}) {
      s.circle(c.x, c.y, 0.035, spot);
    }
  });
  p.line({{0.72, 0.07}, {0.71, 0.02}}, 0.02, spot);  // ossicones
  p.line({{0.77, 0.06}, {0.77, 0.01}}, 0.02, spot);
  p.circle(0.8, 0.11, 0.015, rgb(20, 20, 20));
  p.line({{0.27, 0.56}, {0.2, 0.72}}, 0.02, spot);  // tail
}

void draw_hippo(Painter& p) {
  const cv::Scalar body = rgb(140, 120, 165), dark = rgb(105, 88, 130);
  for (const double x : {0.28, 0.4, 0.58, 0.68}) p.line({{x, 0.62}, {x, 0.8}}, 0.11, body);
  p.ellipse(0.46, 0.52, 0.32, 0.2, body);
  p.ellipse(0.8, 0.5, 0.16, 0.13, body);     // head
  p.ellipse(0.88, 0.57, 0.1, 0.09, dark);    // snout
  p.circle(0.73, 0.36, 0.035, dark);         // ear
  p.circle(0.8, 0.42, 0.022, rgb(20, 20, 20));
  p.circle(0.92, 0.52, 0.014, rgb(40, 30, 50));  // nostril
}

void draw_lion(Painter& p) {
  const cv::Scalar body = rgb(225, 160, 60), mane = rgb(160, 80, 20);
  for (const double x : {0.25, 0.36, 0.52, 0.6}) p.line({{x, 0.6}, {x, 0.85}}, 0.07, body);
  p.line({{0.17, 0.52}, {0.07, 0.38}}, 0.025, body);  // tail
  p.circle(0.07, 0.36, 0.04, mane);                   // tuft
  p.ellipse(0.42, 0.55, 0.24, 0.14, body);
  p.circle(0.7, 0.38, 0.22, mane);   // mane
  p.circle(0.72, 0.39, 0.13, body);  // face
  p.circle(0.68, 0.34, 0.02, rgb(20, 20, 20));
  p.circle(0.78, 0.34, 0.02, rgb(20, 20, 20));
  p.ellipse(0.73, 0.44, 0.04, 0.03, rgb(90, 45, 20));  // nose
}

void draw_crocodile(Painter& p) {
  const cv::Scalar body = rgb(80, 150, 60), dark = rgb(45, 100, 35);
  p.polygon({{0.02, 0.62}, {0.3, 0.48}, {0.62, 0.46}, {0.98, 0.52}, {0.98, 0.6}, {0.62, 0.66}, {0.3, 0.66}}, body);
  for (const double x : {0.36, 0.58}) {
    p.line({{x, 0.62}, {x - 0.05, 0.76}}, 0.05, body);
    p.line({{x + 0.06, 0.62}, {x + 0.1, 0.74}}, 0.05, body);
  }
  p.clipped([&](Painter& s) {
    for (double x = 0.2; x < 0.7; x += 0.07) s.polygon({{x, 0.46}, {x + 0.035, 0.4}, {x + 0.07, 0.46}}, dark);
  });
  for (double x = 0.2; x < 0.7; x += 0.07) p.polygon({{x, 0.49}, {x + 0.035, 0.43}, {x + 0.07, 0.49}}, dark);  // scutes
  p.line({{0.78, 0.56}, {0.97, 0.56}}, 0.008, rgb(20, 20, 20));  // mouth
  for (double x = 0.8; x < 0.96; x += 0.035) p.polygon({{x, 0.56}, {x + 0.012, 0.6}, {x + 0.024, 0.56}}, rgb(255, 255, 255));
  p.circle(0.74, 0.46, 0.03, rgb(240, 230, 80));  // eye
  p.circle(0.74, 0.46, 0.014, rgb(20, 20, 20));
}

void draw_caravan(Painter& p) {
  const cv::Scalar body = rgb(205, 85, 60), cream = rgb(245, 235, 210);
  p.line({{0.02, 0.66}, {0.12, 0.66}}, 0.025, rgb(60, 60, 60));  // tow bar
  p.polygon({{0.12, 0.33}, {0.2, 0.28}, {0.92, 0.28}, {0.97, 0.35}, {0.97, 0.7}, {0.12, 0.7}}, cream);
  p.polygon({{0.12, 0.55}, {0.97, 0.55}, {0.97, 0.7}, {0.12, 0.7}}, body);  // stripe
  p.polygon({{0.22, 0.36}, {0.45, 0.36}, {0.45, 0.5}, {0.22, 0.5}}, rgb(110, 170, 220));  // window
  p.polygon({{0.55, 0.36}, {0.68, 0.36}, {0.68, 0.7}, {0.55, 0.7}}, darker(body, 0.8));  // door
  p.polygon({{0.75, 0.36}, {0.9, 0.36}, {0.9, 0.5}, {0.75, 0.5}}, rgb(110, 170, 220));
  p.circle(0.35, 0.72, 0.09, rgb(30, 30, 30));  // wheel
  p.circle(0.35, 0.72, 0.035, rgb(170, 170, 170));
}

void draw_ball(Painter& p, const cv::Scalar& colour) {
  p.circle(0.5, 0.45, 0.4, rgb(250, 250, 250));
  p.clipped([&](Painter& s) {
    s.polygon({{0.5, 0.45}, {0.0, 0.0}, {0.5, 0.0}}, colour);
    s.polygon({{0.5, 0.45}, {1.0, 0.45}, {1.0, 0.9}}, rgb(250, 210, 40));
    s.polygon({{0.5, 0.45}, {0.0, 0.9}, {0.0, 0.6}}, rgb(50, 100, 200));
  });
}

void draw_face(Painter& p, bool girl, const cv::Scalar& colour) {
  const cv::Scalar skin = rgb(250, 215, 180), hair = girl ? rgb(230, 170, 50) : rgb(110, 65, 30);
  if (girl) {
    p.circle(0.15, 0.5, 0.1, hair);  // pigtails
    p.circle(0.85, 0.5, 0.1, hair);
    p.circle(0.15, 0.38, 0.05, colour);  // bows
    p.circle(0.85, 0.38, 0.05, colour);
  }
  p.circle(0.5, 0.45, 0.33, skin);
  p.clipped([&](Painter& s) {
    s.ellipse(0.5, girl ? 0.18 : 0.14, 0.4, girl ? 0.17 : 0.15, hair);
  });
  if (!girl) p.ellipse(0.5, 0.13, 0.3, 0.06, colour);  // cap brim in the item colour
  p.circle(0.39, 0.44, 0.035, rgb(30, 30, 30));
  p.circle(0.61, 0.44, 0.035, rgb(30, 30, 30));
  std::vector<cv::Point2d> smile;
  for (int i = 0; i <= 8; ++i) {
    const double a = std::numbers::pi * (0.15 + 0.7 * i / 8.0);
    smile.emplace_back(0.5 + 0.15 * std::cos(a), 0.52 + 0.12 * std::sin(a));
  }
  p.line(smile, 0.025, rgb(180, 60, 60));
}

}  // namespace

cv::Mat draw_item_picture(const ItemSpec& spec, int side_px) {
  if (side_px < 4 || side_px > 4096) {
    throw InputError("picture side " + std::to_string(side_px) + " px is out of range", "side_px", "4…4096");
  }
  Painter p(side_px);
  const cv::Scalar colour = rgb(spec.colour[0], spec.colour[1], spec.colour[2]);
  if (spec.name == "zebra") {
    draw_zebra(p);
  } else if (spec.name == "elephant") {
    draw_elephant(p);
  } else if (spec.name == "giraffe") {
    draw_giraffe(p);
  } else if (spec.name == "hippo") {
    draw_hippo(p);
  } else if (spec.name == "lion") {
    draw_lion(p);
  } else if (spec.name == "crocodile") {
    draw_crocodile(p);
  } else if (spec.name == "caravan") {
    draw_caravan(p);
  } else if (spec.name == "ball") {
    draw_ball(p, colour);
  } else if (spec.name == "boy" || spec.name == "girl") {
    draw_face(p, spec.name == "girl", colour);
  } else {
    p.ellipse(0.5, 0.45, 0.4, 0.32, colour);  // any other item: a blob in its colour
  }
  if (side_px >= 24) p.label(spec.label.empty() ? spec.name : spec.label, 0.5, 0.92, 0.8);
  return p.bgra();
}

namespace {

/// A PNG file as 8-bit BGRA (libpng's simplified reader: any bit depth, colour type and palette, transparency as
/// alpha), or an empty image when the file is not a PNG it can read. libpng alone, not OpenCV's image codecs, so
/// that the simulation does not load their 140 shared libraries at start-up.
cv::Mat read_png_bgra(const std::filesystem::path& file) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&image, file.c_str()) == 0) return {};
  image.format = PNG_FORMAT_BGRA;
  cv::Mat bgra(static_cast<int>(image.height), static_cast<int>(image.width), CV_8UC4);
  const auto row_stride = static_cast<png_int_32>(bgra.step[0]);
  if (png_image_finish_read(&image, nullptr, bgra.data, row_stride, nullptr) == 0) {
    png_image_free(&image);
    return {};
  }
  return bgra;
}

}  // namespace

cv::Mat item_picture(const ItemSpec& spec, int side_px) {
  if (!spec.picture.empty()) {
    const std::filesystem::path file = assets_dir() / spec.picture;
    std::error_code ignored;
    if (std::filesystem::is_regular_file(file, ignored)) {
      if (const cv::Mat loaded = read_png_bgra(file); !loaded.empty()) {
        // Fit into the square box, keeping the aspect (QML Image PreserveAspectFit), centred.
        const double fit = static_cast<double>(side_px) / std::max(loaded.cols, loaded.rows);
        const cv::Size size(std::max(1, static_cast<int>(std::lround(loaded.cols * fit))),
                            std::max(1, static_cast<int>(std::lround(loaded.rows * fit))));
        cv::Mat scaled;
        cv::resize(loaded, scaled, size, 0, 0, fit < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
        cv::Mat out(side_px, side_px, CV_8UC4, cv::Scalar(0, 0, 0, 0));
        scaled.copyTo(out(cv::Rect((side_px - size.width) / 2, (side_px - size.height) / 2, size.width, size.height)));
        return out;
      }
    }
  }
  return draw_item_picture(spec, side_px);
}

}  // namespace freeplay::sim
