// Background images: vector map descriptions (assets/backgrounds/*.yaml) rasterised with OpenCV.

#include "freeplay/sim/background.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

#include <opencv2/imgproc.hpp>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::sim {
namespace {

constexpr int kMinWidthPx = 16;
constexpr int kMaxWidthPx = 16384;
constexpr int kShiftBits = 4;  // sub-pixel precision of OpenCV drawing calls
constexpr double kShiftScale = 1 << kShiftBits;
constexpr int kCurveSamplesPerSegment = 12;

double read_number(const std::string& file, const YAML::Node& node, const std::string& key) {
  try {
    if (!node.IsScalar()) throw YAML::Exception(node.Mark(), "not a scalar");
    const double value = node.as<double>();
    if (!std::isfinite(value)) throw YAML::Exception(node.Mark(), "not finite");
    return value;
  } catch (const YAML::Exception&) {
    throw InputError("expected a finite number", key, "a number", location_of(node, file));
  }
}

cv::Point2d read_point(const std::string& file, const YAML::Node& node, const std::string& key) {
  if (!node.IsSequence() || node.size() != 2) {
    throw InputError("expected a point [x, y]", key, "[x, y] in map units", location_of(node, file));
  }
  return {read_number(file, node[0], key + "[0]"), read_number(file, node[1], key + "[1]")};
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

cv::Scalar read_colour(const std::string& file, const YAML::Node& node, const std::string& key) {
  const std::string text = node.IsScalar() ? node.Scalar() : std::string();
  bool ok = text.size() == 7 && text[0] == '#';
  int rgb[3] = {0, 0, 0};
  for (int i = 0; ok && i < 3; ++i) {
    const int hi = hex_digit(text[static_cast<std::size_t>(1 + 2 * i)]);
    const int lo = hex_digit(text[static_cast<std::size_t>(2 + 2 * i)]);
    ok = hi >= 0 && lo >= 0;
    rgb[i] = hi * 16 + lo;
  }
  if (!ok) throw InputError("expected a colour", key, "\"#rrggbb\"", location_of(node, file));
  return {static_cast<double>(rgb[2]), static_cast<double>(rgb[1]), static_cast<double>(rgb[0])};
}

const YAML::Node require(const std::string& file, const YAML::Node& map, const std::string& name,
                         const std::string& key_prefix) {
  const YAML::Node child = map[name];
  if (!child) throw InputError("missing key", key_prefix + name, {}, location_of(map, file));
  return child;
}

void reject_unknown_keys(const std::string& file, const YAML::Node& map, const std::vector<std::string>& allowed,
                         const std::string& key_prefix) {
  for (const auto& kv : map) {
    const std::string name = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError("unknown key", key_prefix + name, list, location_of(kv.first, file));
    }
  }
}

MapShape read_shape(const std::string& file, const YAML::Node& node, const std::string& key) {
  if (!node.IsMap()) throw InputError("expected a shape mapping", key, {}, location_of(node, file));
  reject_unknown_keys(file, node,
                      {"type", "layer", "fill", "stroke", "width", "points", "centre", "radii", "angle", "smooth"},
                      key + ".");
  MapShape shape;
  const YAML::Node type = require(file, node, "type", key + ".");
  const std::string type_name = type.IsScalar() ? type.Scalar() : std::string();
  if (type_name == "polygon") {
    shape.kind = MapShape::Kind::Polygon;
  } else if (type_name == "ellipse") {
    shape.kind = MapShape::Kind::Ellipse;
  } else if (type_name == "polyline") {
    shape.kind = MapShape::Kind::Polyline;
  } else {
    throw InputError("unknown shape type '" + type_name + "'", key + ".type", "polygon, ellipse, polyline",
                     location_of(type, file));
  }
  if (const YAML::Node layer = node["layer"]) shape.layer = layer.as<std::string>();
  if (const YAML::Node smooth = node["smooth"]) {
    try {
      shape.smooth = smooth.as<bool>();
    } catch (const YAML::Exception&) {
      throw InputError("expected true or false", key + ".smooth", "true, false", location_of(smooth, file));
    }
  }
  if (shape.kind == MapShape::Kind::Polyline) {
    shape.bgr = read_colour(file, require(file, node, "stroke", key + "."), key + ".stroke");
    const YAML::Node width = require(file, node, "width", key + ".");
    shape.width = read_number(file, width, key + ".width");
    if (shape.width <= 0.0) throw InputError("must be positive", key + ".width", "> 0", location_of(width, file));
  } else {
    shape.bgr = read_colour(file, require(file, node, "fill", key + "."), key + ".fill");
    if (const YAML::Node width = node["width"]) {
      shape.width = read_number(file, width, key + ".width");  // ellipse outline (rings)
      if (shape.width < 0.0) throw InputError("must not be negative", key + ".width", ">= 0", location_of(width, file));
    }
  }
  if (shape.kind == MapShape::Kind::Ellipse) {
    shape.points = {read_point(file, require(file, node, "centre", key + "."), key + ".centre")};
    const YAML::Node radii = require(file, node, "radii", key + ".");
    const cv::Point2d r = read_point(file, radii, key + ".radii");
    if (r.x <= 0.0 || r.y <= 0.0) throw InputError("radii must be positive", key + ".radii", "> 0",
                                                   location_of(radii, file));
    shape.radii = {r.x, r.y};
    if (const YAML::Node angle = node["angle"]) shape.angle_deg = read_number(file, angle, key + ".angle");
  } else {
    const YAML::Node points = require(file, node, "points", key + ".");
    const std::size_t needed = shape.kind == MapShape::Kind::Polygon ? 3 : 2;
    if (!points.IsSequence() || points.size() < needed) {
      throw InputError("needs at least " + std::to_string(needed) + " points", key + ".points", "[[x, y], ...]",
                       location_of(points, file));
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      shape.points.push_back(read_point(file, points[i], key + ".points[" + std::to_string(i) + "]"));
    }
  }
  return shape;
}

/// Samples a Catmull-Rom spline through `control` (closed or open).
std::vector<cv::Point2d> catmull_rom(const std::vector<cv::Point2d>& control, bool closed) {
  const std::size_t n = control.size();
  if (n < 3) return control;
  auto at = [&](std::ptrdiff_t i) {
    if (closed) return control[static_cast<std::size_t>((i % static_cast<std::ptrdiff_t>(n) + n) % n)];
    return control[static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(i, 0, static_cast<std::ptrdiff_t>(n) - 1))];
  };
  std::vector<cv::Point2d> out;
  const std::size_t segments = closed ? n : n - 1;
  for (std::size_t s = 0; s < segments; ++s) {
    const auto i = static_cast<std::ptrdiff_t>(s);
    const cv::Point2d p0 = at(i - 1), p1 = at(i), p2 = at(i + 1), p3 = at(i + 2);
    for (int k = 0; k < kCurveSamplesPerSegment; ++k) {
      const double t = static_cast<double>(k) / kCurveSamplesPerSegment;
      const double t2 = t * t, t3 = t2 * t;
      out.push_back(0.5 * ((2.0 * p1) + (-p0 + p2) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                           (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * t3));
    }
  }
  if (!closed) out.push_back(control.back());
  return out;
}

std::vector<cv::Point> to_fixed_point(const std::vector<cv::Point2d>& points, double scale) {
  std::vector<cv::Point> out;
  out.reserve(points.size());
  for (const auto& p : points) {
    out.emplace_back(static_cast<int>(std::lround(p.x * scale * kShiftScale)),
                     static_cast<int>(std::lround(p.y * scale * kShiftScale)));
  }
  return out;
}

void draw_shape(cv::Mat& image, const MapShape& shape, double scale) {
  switch (shape.kind) {
    case MapShape::Kind::Polygon: {
      const auto outline = shape.smooth ? catmull_rom(shape.points, true) : shape.points;
      const std::vector<std::vector<cv::Point>> polys = {to_fixed_point(outline, scale)};
      cv::fillPoly(image, polys, shape.bgr, cv::LINE_AA, kShiftBits);
      break;
    }
    case MapShape::Kind::Polyline: {
      const auto line = shape.smooth ? catmull_rom(shape.points, false) : shape.points;
      const std::vector<std::vector<cv::Point>> lines = {to_fixed_point(line, scale)};
      const int thickness = std::max(1, static_cast<int>(std::lround(shape.width * scale)));
      cv::polylines(image, lines, false, shape.bgr, thickness, cv::LINE_AA, kShiftBits);
      break;
    }
    case MapShape::Kind::Ellipse: {
      const cv::Point centre = to_fixed_point(shape.points, scale).front();
      const cv::Size axes(static_cast<int>(std::lround(shape.radii.width * scale * kShiftScale)),
                          static_cast<int>(std::lround(shape.radii.height * scale * kShiftScale)));
      const int thickness = shape.width > 0.0 ? std::max(1, static_cast<int>(std::lround(shape.width * scale)))
                                              : cv::FILLED;
      cv::ellipse(image, centre, axes, shape.angle_deg, 0.0, 360.0, shape.bgr, thickness, cv::LINE_AA, kShiftBits);
      break;
    }
  }
}

void check_width(int width_px) {
  if (width_px < kMinWidthPx || width_px > kMaxWidthPx) {
    throw InputError("raster width " + std::to_string(width_px) + " px is out of range", "width",
                     std::to_string(kMinWidthPx) + "…" + std::to_string(kMaxWidthPx) + " px");
  }
}

}  // namespace

std::string_view background_name(BackgroundKind kind) {
  switch (kind) {
    case BackgroundKind::Blank: return "blank";
    case BackgroundKind::FreeplayMap: return "map";
    case BackgroundKind::Tutorial: return "tutorial";
  }
  return "blank";
}

std::optional<BackgroundKind> background_from_name(std::string_view name) {
  for (const auto kind : {BackgroundKind::Blank, BackgroundKind::FreeplayMap, BackgroundKind::Tutorial}) {
    if (background_name(kind) == name) return kind;
  }
  return std::nullopt;
}

int raster_height(int width_px) {
  return static_cast<int>(std::lround(width_px * kScreenHeightM / kScreenWidthM));
}

MapDescription MapDescription::load(const std::filesystem::path& path) {
  const std::string file = path.string();
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw InputError("cannot read the map description", "file", {}, {file, 0, 0});
  } catch (const YAML::ParserException& e) {
    throw InputError("YAML syntax error: " + e.msg, {}, {}, {file, e.mark.line + 1, e.mark.column + 1});
  }
  if (!root.IsMap()) throw InputError("expected a mapping at the top level", {}, {}, location_of(root, file));
  reject_unknown_keys(file, root, {"name", "size", "background", "shapes"}, "");
  MapDescription map;
  if (const YAML::Node name = root["name"]) map.name = name.as<std::string>();
  const YAML::Node size = require(file, root, "size", "");
  const cv::Point2d extent = read_point(file, size, "size");
  if (extent.x <= 0.0 || extent.y <= 0.0) {
    throw InputError("size must be positive", "size", "[width > 0, height > 0]", location_of(size, file));
  }
  map.size = {extent.x, extent.y};
  map.background_bgr = read_colour(file, require(file, root, "background", ""), "background");
  if (const YAML::Node shapes = root["shapes"]) {
    if (!shapes.IsSequence()) throw InputError("expected a list of shapes", "shapes", {}, location_of(shapes, file));
    for (std::size_t i = 0; i < shapes.size(); ++i) {
      map.shapes.push_back(read_shape(file, shapes[i], "shapes[" + std::to_string(i) + "]"));
    }
  }
  return map;
}

cv::Mat render_map(const MapDescription& map, int width_px) {
  check_width(width_px);
  cv::Mat image(raster_height(width_px), width_px, CV_8UC3, map.background_bgr);
  const double scale = width_px / map.size.width;
  for (const auto& shape : map.shapes) draw_shape(image, shape, scale);
  return image;
}

namespace {

cv::Mat rasterise_background(BackgroundKind kind, int width_px) {
  switch (kind) {
    case BackgroundKind::Blank: return cv::Mat(raster_height(width_px), width_px, CV_8UC3, cv::Scalar(0, 0, 0));
    case BackgroundKind::FreeplayMap:
      return render_map(MapDescription::load(asset_path("backgrounds/freeplay_map.yaml")), width_px);
    case BackgroundKind::Tutorial:
      return render_map(MapDescription::load(asset_path("backgrounds/tutorial.yaml")), width_px);
  }
  return {};
}

}  // namespace

cv::Mat render_background(BackgroundKind kind, int width_px) { return shared_background(kind, width_px).clone(); }

cv::Mat shared_background(BackgroundKind kind, int width_px) {
  check_width(width_px);
  // Every episode shows the same few backgrounds: each is read and rasterised once per process (and assets folder).
  static std::mutex mutex;
  static std::map<std::tuple<int, int, std::string>, cv::Mat> rendered;
  const auto key = std::make_tuple(static_cast<int>(kind), width_px,
                                   kind == BackgroundKind::Blank ? std::string() : asset_path("backgrounds").string());
  std::lock_guard lock(mutex);
  auto it = rendered.find(key);
  if (it == rendered.end()) it = rendered.emplace(key, rasterise_background(kind, width_px)).first;
  return it->second;
}

}  // namespace freeplay::sim
