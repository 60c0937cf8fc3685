// `freeplay plan`: plans (and optionally executes) one robot move on a random tray layout; metrics, JSON, a picture.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "command_registry.hpp"
#include "freeplay/runner/move_driver.hpp"
#include "freeplay/runner/sandtray_world.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/planning/layout.hpp"
#include "freeplay/planning/move_executor.hpp"
#include "freeplay/planning/occupancy_grid.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::cli {
namespace {

struct PlanOptions {
  std::string item;
  std::string to;
  std::string to_px;
  std::string planner = planning::PlannerSettings{}.name;
  std::uint64_t layout_seed = 1;
  int items = 10;
  double time_budget_s = planning::kDefaultTimeBudgetS;
  bool execute = false;
  bool json = false;
  bool faithful_endpoints = false;
  std::string out;
  int width = 1200;
};

constexpr double kMaxExecutionS = 120.0;  // a move longer than this is reported as not released

// "X,Y" → two finite numbers; throws InputError naming `key`.
Vec2 parse_point(const std::string& text, const std::string& key, const std::string& unit) {
  std::istringstream in(text);
  double x = 0.0;
  double y = 0.0;
  char comma = 0;
  std::string rest;
  if (!(in >> x >> comma >> y) || comma != ',' || (in >> rest) || !std::isfinite(x) || !std::isfinite(y)) {
    throw InputError(fmt::format("'{}' is not a point", text), key, fmt::format("X,Y with finite numbers ({})", unit));
  }
  return {x, y};
}

// Items `n` of a random layout of every catalogue item that include `item` (the first n − 1 others in placement
// order, so the subset is random too).
planning::Layout layout_with(const sim::ItemCatalogue& catalogue, const std::string& item, int n, Rng& rng) {
  std::vector<planning::ItemShape> shapes;
  for (const auto& spec : catalogue.items()) shapes.push_back({spec.name, spec.polygon});
  const planning::Layout all = planning::random_layout(shapes, static_cast<int>(shapes.size()), rng);
  planning::Layout out;
  for (const auto& placed : all.items) {
    if (placed.name == item) out.items.push_back(placed);
  }
  for (const auto& placed : all.items) {
    if (static_cast<int>(out.items.size()) >= n) break;
    if (placed.name != item) out.items.push_back(placed);
  }
  return out;
}

cv::Point to_pixel(const Vec2& p, double pixels_per_metre) {
  return {static_cast<int>(std::lround(p.x() * pixels_per_metre)),
          static_cast<int>(std::lround(-p.y() * pixels_per_metre))};
}

// The screen with the occupancy grid (red, alpha ∝ occupancy) and the path (start dot, target cross) drawn on top.
cv::Mat draw_plan(const sim::Sandtray& tray, const planning::OccupancyGrid& grid,
                  const std::vector<planning::TimedPose>& path, const Vec2& start, const Vec2& target, int width) {
  cv::Mat screen = tray.render_screen(width);
  const double ppm = static_cast<double>(width) / sim::kScreenWidthM;
  cv::Mat overlay = screen.clone();
  for (int row = 0; row < planning::OccupancyGrid::kRows; ++row) {
    for (int col = 0; col < planning::OccupancyGrid::kCols; ++col) {
      const int occupancy = grid.occupancy({col, row});
      if (occupancy == 0) continue;
      const Vec2 corner = planning::OccupancyGrid::cell_point({col, row});
      const cv::Point a = to_pixel(corner, ppm);
      const cv::Point b = to_pixel(corner + Vec2(planning::OccupancyGrid::kResolutionM,
                                                 -planning::OccupancyGrid::kResolutionM), ppm);
      const double alpha = 0.6 * occupancy / 100.0;
      cv::Mat cell = overlay(cv::Rect(a, b) & cv::Rect(0, 0, overlay.cols, overlay.rows));
      cv::addWeighted(cell, 1.0 - alpha, cv::Mat(cell.size(), cell.type(), cv::Scalar(0, 0, 255)), alpha, 0.0, cell);
    }
  }
  screen = overlay;
  const int thickness = std::max(2, width / 400);
  std::vector<cv::Point> points;
  for (const auto& pose : path) points.push_back(to_pixel(pose.position, ppm));
  if (points.size() > 1) cv::polylines(screen, points, false, cv::Scalar(255, 0, 255), thickness, cv::LINE_AA);
  for (const auto& p : points) cv::circle(screen, p, thickness, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
  cv::circle(screen, to_pixel(start, ppm), 3 * thickness, cv::Scalar(255, 0, 255), cv::FILLED, cv::LINE_AA);
  cv::drawMarker(screen, to_pixel(target, ppm), cv::Scalar(0, 255, 255), cv::MARKER_CROSS, 8 * thickness,
                 thickness, cv::LINE_AA);
  return screen;
}

void check_png_path(const std::filesystem::path& out) {
  if (out.extension() != ".png" && out.extension() != ".PNG") {
    throw InputError("the output file '" + out.string() + "' is not a .png file", "--out", "a path ending in .png");
  }
  const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw InputError("the folder '" + folder.string() + "' does not exist", "--out", "a path in an existing folder");
  }
}

// The move of `freeplay plan`: on the tray alone, its finger poses are the game's `/poses` (no robot body).
class TrayOnly final : public runner::MoveSink {
 public:
  explicit TrayOnly(sim::Sandtray& tray) : tray_(tray), world_(runner::sandtray_move_world(tray)) {}
  planning::MoveWorld move_world() override { return world_; }
  void move_started(const policies::MoveItem& /*move*/, bool /*running*/, double /*t*/) override {}
  void finger(const planning::TimedPose& pose, double /*t*/) override { tray_.robot_pose(pose.position); }
  void move_ended(const policies::MoveItem& /*move*/, planning::MoveStatus /*status*/, events::MoveResult /*result*/,
                  double /*t*/) override {}

 private:
  sim::Sandtray& tray_;
  planning::MoveWorld world_;
};

std::string millimetres(double metres) {
  return std::isfinite(metres) ? fmt::format("{:.1f} mm", metres * 1e3) : std::string("∞ (no other item)");
}

void run_plan(const PlanOptions& options) {
  // Every argument is checked before any work (exit 2 with the allowed values).
  auto catalogue = std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default());
  if (catalogue->find(options.item) == nullptr) {
    throw InputError(fmt::format("unknown item '{}'", options.item), "--item", catalogue->names());
  }
  if (options.to.empty() == options.to_px.empty()) {
    throw InputError("give the target once", "--to / --to-px", "either --to X,Y (m) or --to-px X,Y (px)");
  }
  const Vec2 target = options.to.empty()
                          ? Vec2(parse_point(options.to_px, "--to-px", "screen pixels at 1920 px, y down") *
                                 sim::kMetresPerPixel)
                                .cwiseProduct(Vec2(1.0, -1.0))
                          : parse_point(options.to, "--to", "metres in the sandtray frame, y <= 0 on screen");
  const auto names = planning::planner_names();
  if (std::find(names.begin(), names.end(), options.planner) == names.end()) {
    throw InputError(fmt::format("unknown planner '{}'", options.planner), "--planner",
                     planning::planner_names_joined());
  }
  auto planner = std::shared_ptr<const planning::MotionPlanner>(planning::make_planner(options.planner));
  const int max_items = static_cast<int>(catalogue->items().size());
  if (options.items < 1 || options.items > max_items) {
    throw InputError(fmt::format("{} items", options.items), "--items", fmt::format("1…{}", max_items));
  }
  if (!(options.time_budget_s > 0.0) || !std::isfinite(options.time_budget_s)) {
    throw InputError(fmt::format("{} s", options.time_budget_s), "--time-budget", "> 0 seconds");
  }
  if (options.width < 16 || options.width > 16384) {
    throw InputError(fmt::format("width {} px is out of range", options.width), "--width", "16…16384");
  }
  if (!options.out.empty()) check_png_path(options.out);

  // The tray: free play, the layout teleported in (setup only), the others in the stash.
  const SeedSequence seeds(options.layout_seed);
  sim::SandtrayConfig tray_config;
  tray_config.raster_width_px = options.out.empty() ? 240 : std::max(options.width, 240);
  sim::Sandtray tray(catalogue, tray_config, seeds.stream("sandtray"));
  tray.signal(sim::Signal::StartFreeplay);
  Rng layout_rng = seeds.stream("layout");
  const planning::Layout layout = layout_with(*catalogue, options.item, options.items, layout_rng);
  for (const auto& placed : layout.items) tray.place_item(placed.name, placed.pose);
  TrayOnly sink(tray);
  const planning::MoveWorld world = sink.move_world();
  const Vec2 start = *world.item_centre(options.item);
  const std::vector<planning::Obstacle> footprints_before = world.footprints();

  planning::MoveExecutorConfig config;
  config.time_budget_s = options.time_budget_s;
  config.exact_endpoints = !options.faithful_endpoints;
  runner::MoveDriver mover(std::make_unique<planning::MoveExecutor>(planner, config), seeds.stream("planner"));
  mover.start({options.item, target}, 0.0, sink);
  const planning::MoveOutcome planned = mover.outcome();
  const planning::PlanMetrics& metrics = planned.plan.metrics;
  const std::size_t n_poses = planned.poses.size();
  const double expected_s = n_poses > 0 ? planned.poses.back().t - planned.poses.front().t : 0.0;

  nlohmann::json report = {
      {"item", options.item},
      {"start", {start.x(), start.y()}},
      {"target", {target.x(), target.y()}},
      {"planner", options.planner},
      {"layout_seed", options.layout_seed},
      {"items_on_map", layout.items.size()},
      {"ok", planned.plan.ok},
      {"reason", planned.reason()},
      {"message", planned.plan.message},
      {"planning_time_ms", metrics.planning_time_s * 1e3},
      {"poses", n_poses},
  };
  if (planned.plan.ok) {
    report["path_length_m"] = metrics.path_length_m;
    report["min_clearance_m"] =
        std::isfinite(metrics.min_clearance_m) ? nlohmann::json(metrics.min_clearance_m) : nlohmann::json(nullptr);
    report["expected_execution_s"] = expected_s;
  }

  if (!options.out.empty()) {  // the tray as the planner saw it, before any execution
    const auto grid = planning::OccupancyGrid::build(footprints_before, options.item);
    const cv::Mat image = draw_plan(tray, grid, planned.poses, start, target, options.width);
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", image, png)) throw std::runtime_error("PNG encoding failed");
    write_file_atomically(options.out, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    report["out"] = options.out;
  }

  std::optional<double> release_time;
  double others_moved_m = 0.0;
  if (options.execute && planned.plan.ok) {
    const std::string releasing = "releasing_" + options.item;
    const double t0 = tray.time();
    for (int tick = 0; tick < std::lround(kMaxExecutionS / runner::kMoveTickS) && !release_time; ++tick) {
      mover.step(tray.time() - t0, sink);
      tray.step(runner::kMoveTickS);
      for (const Event& event : tray.drain_events()) {
        const auto* message = event.get<events::InteractionEvent>();
        if (message && message->message == releasing) {
          release_time = event.t - t0;
          mover.observe_release(tray.item(options.item).pose.position());
        }
      }
    }
    for (const auto& before : footprints_before) {
      if (before.name == options.item) continue;
      const Vec2 was = vertex_mean(before.footprint);
      for (const auto& after : world.footprints()) {
        if (after.name == before.name) others_moved_m = std::max(others_moved_m, (vertex_mean(after.footprint) - was).norm());
      }
    }
    const planning::MoveOutcome& done = mover.outcome();
    report["executed"] = {
        {"status", std::string(planning::move_status_name(done.status))},
        {"execution_s", done.execution_duration_s},
        {"release_s", release_time ? nlohmann::json(*release_time) : nlohmann::json(nullptr)},
        {"placement_error_m",
         done.placement_error_m ? nlohmann::json(*done.placement_error_m) : nlohmann::json(nullptr)},
        {"final_centre", {tray.item(options.item).pose.x, tray.item(options.item).pose.y}},
        {"others_moved_max_m", others_moved_m},
    };
  }

  if (options.json) {
    std::cout << report.dump(2) << "\n";
  } else {
    std::cout << fmt::format("plan {} ({:.4f}, {:.4f}) -> ({:.4f}, {:.4f}) with {}, layout seed {} ({} items on the map)\n",
                             options.item, start.x(), start.y(), target.x(), target.y(), options.planner,
                             options.layout_seed, layout.items.size());
    const auto row = [](const std::string& name, const std::string& value) {
      std::cout << fmt::format("  {:<22} {}\n", name, value);
    };
    row("result", planned.plan.ok ? "path found" : "no path (" + planned.reason() + ")");
    row("planning time", fmt::format("{:.3f} ms", metrics.planning_time_s * 1e3));
    if (planned.plan.ok) {
      row("path length", fmt::format("{:.3f} m", metrics.path_length_m));
      row("min clearance", millimetres(metrics.min_clearance_m));
      row("finger poses", fmt::format("{} at 10 Hz", n_poses));
      row("expected execution", fmt::format("{:.1f} s (+ 1.0 s until the release)", expected_s));
    }
    if (report.contains("executed")) {
      const planning::MoveOutcome& done = mover.outcome();
      row("executed", std::string(planning::move_status_name(done.status)));
      row("released after", release_time ? fmt::format("{:.1f} s", *release_time) : std::string("not released"));
      row("placement error", done.placement_error_m ? millimetres(*done.placement_error_m) : std::string("–"));
      row("other items moved", fmt::format("up to {}", millimetres(others_moved_m)));
    }
    if (!options.out.empty()) row("picture", options.out);
  }
  if (!planned.plan.ok) {
    std::cerr << fmt::format("error: no path for '{}': {}: {}\n", options.item, planned.reason(), planned.message);
    fail_with(1);
  }
}

const RegisterCommand kPlanCommand(40, [](CLI::App& program) {
  auto options = std::make_shared<PlanOptions>();
  auto* command = program.add_subcommand(
      "plan",
      "Plan one robot move (move_sandbox_items) on a random tray layout and print its metrics.\n"
      "Items are placed from --layout SEED with the real catalogue polygons; the planner sees the other items'\n"
      "footprints as the real one does. Exit 0 with a path, 1 when there is none (the reason is printed),\n"
      "2 on bad input. Example: freeplay plan --item hippo --to 0.40,-0.12 --planner rrtconnect --out plan.png");
  command->add_option("--item", options->item, "Item to move (zebra, elephant, giraffe, hippo, lion, crocodile, "
                                                "caravan, ball, boy, girl)")
      ->required();
  command->add_option("--to", options->to, "Target of the item centre: X,Y in metres, sandtray frame (origin top "
                                           "left, x right, y up: on screen 0…0.6, -0.335…0)");
  command->add_option("--to-px", options->to_px, "Target in screen pixels at 1920 px wide: X,Y with y down");
  command->add_option("--planner", options->planner, "Planner: " + planning::planner_names_joined())
      ->capture_default_str();
  command->add_option("--layout", options->layout_seed, "Seed of the layout (and of the tray and the planner)")
      ->capture_default_str();
  command->add_option("--items", options->items, "Number of items on the map (the moved one included), 1…10")
      ->capture_default_str();
  command->add_option("--time-budget", options->time_budget_s, "Planning budget in seconds")->capture_default_str();
  command->add_flag("--execute", options->execute,
                    "Also run the move in the physics (10 Hz finger poses, 1 s auto-release) and report the "
                    "placement error");
  command->add_flag("--faithful-endpoints", options->faithful_endpoints,
                    "Stream the A* path's first/last poses at their cell corners, as the real system (default: "
                    "item centre and exact target)");
  command->add_flag("--json", options->json, "Print the metrics as JSON");
  command->add_option("--out", options->out,
                      "Draw the occupancy grid and the path over the screen image into this PNG (written atomically)");
  command->add_option("--width", options->width, "Width of the --out picture in pixels")->capture_default_str();
  command->callback([options] { run_plan(*options); });
});

}  // namespace
}  // namespace freeplay::cli
