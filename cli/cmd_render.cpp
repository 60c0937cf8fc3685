// `freeplay render`: off-screen images of the 3-D stage's cameras (a fresh stage, or a moment of a scenario's
// episode); `freeplay list cameras`.

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "command_registry.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "freeplay/stage/camera_settings.hpp"
#include "freeplay/stage/renderer.hpp"
#include "freeplay/stage/stage.hpp"
#include "scenario_moment.hpp"

namespace freeplay::cli {
namespace {

using namespace freeplay::stage;

struct RenderArgs {
  std::string scene = "child-robot";
  std::vector<std::string> cameras;
  bool depth = false;
  std::string preset{to_string(stage::RenderingSettings{}.preset)};  // a scenario's default (`rendering.preset`)
  int width = 0;
  int height = 0;
  double age = 7.0;
  std::string gl;
  std::string out;
  bool list = false;
  std::optional<std::uint64_t> seed;
  bool stash = false;
  MomentOptions moment;
  bool scene_given = false;
  bool age_given = false;
  bool preset_given = false;
};

constexpr std::string_view kCameraPlaceholder = "{camera}";

// The output file of `camera`: --out with "{camera}" replaced (required when several cameras are rendered).
std::string output_for(const RenderArgs& args, const std::string& camera) {
  std::string out = args.out;
  const auto at = out.find(kCameraPlaceholder);
  if (at != std::string::npos) out.replace(at, kCameraPlaceholder.size(), camera);
  return out;
}

// Writes a frame as PNG: RGB as 8-bit colour, depth as 16-bit millimetres (0 = nothing).
void write_png(const FramePack& frame, bool depth, const std::string& out, const std::string& gl_renderer,
               const std::string& context) {
  cv::Mat image;
  if (depth) {
    frame.depth_m.convertTo(image, CV_16UC1, 1000.0);  // millimetres, saturating at 65.535 m
  } else {
    cv::cvtColor(frame.rgb, image, cv::COLOR_RGB2BGR);
  }
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) throw std::runtime_error("PNG encoding failed");
  write_file_atomically(out, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
  spdlog::info("wrote {} ({}x{}, camera {}{}, GL renderer: {})", out, image.cols, image.rows, frame.camera, context,
               gl_renderer);
}

// The largest image any of `cameras` produces (colour at the requested size, depth at its stream's size).
RendererOptions sized_for(RendererOptions options, const StageModel& model, const std::vector<std::string>& cameras,
                          const std::vector<RenderRequest>& requests) {
  options.max_width = 1;
  options.max_height = 1;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const auto& spec = model.camera(cameras[i]);
    const RenderRequest& request = requests[i];
    const int width = request.width > 0 ? request.width : spec.color.width;
    const int height = request.height > 0 ? request.height : spec.color.height;
    const bool depth_follows = spec.depth.width == spec.color.width && spec.depth.height == spec.color.height;
    options.max_width = std::max({options.max_width, width, depth_follows ? width : spec.depth.width});
    options.max_height = std::max({options.max_height, height, depth_follows ? height : spec.depth.height});
  }
  return options;
}

// `--scenario`: runs the scenario's episode to the moment and renders its cameras there.
void render_scenario_moment(const RenderArgs& args) {
  if (args.scene_given || args.age_given) {
    throw InputError("--scene and --age come from the scenario", args.scene_given ? "--scene" : "--age",
                     "leave them out with --scenario");
  }
  if (args.stash) throw InputError("--stash shows a fresh tray", "--stash", "leave it out with --scenario");
  if (args.out.empty()) throw InputError("missing --out FILE.png", "--out");
  if (args.cameras.size() > 1 && args.out.find(kCameraPlaceholder) == std::string::npos) {
    throw InputError("several cameras need one file each", "--out", "a path with {camera}, e.g. out/{camera}.png");
  }
  std::vector<FramePack> frames;
  std::vector<std::string> cameras = args.cameras;
  std::string gl_renderer;
  const auto context = capture_moment(args.moment, args.seed, [&](const scenario::Scenario& scenario,
                                                                  const runner::EpisodeSnapshot& snapshot) {
    if (cameras.empty()) {
      for (const auto& c : scenario.cameras) cameras.push_back(c.name);
      if (cameras.empty()) throw InputError("the scenario lists no cameras", "--camera", "a camera name");
      if (cameras.size() > 1 && args.out.find(kCameraPlaceholder) == std::string::npos) {
        throw InputError("the scenario lists several cameras: one file each", "--out",
                         "a path with {camera}, e.g. out/{camera}.png");
      }
    }
    RendererOptions options = runner::renderer_options(scenario.rendering);
    if (!args.gl.empty()) options.backend = gl_backend_from_name(args.gl);
    if (args.preset_given) options.preset = visual_preset_from_name(args.preset);
    auto model = StageModel::create(runner::stage_config_for(snapshot));
    std::vector<RenderRequest> requests;
    for (const auto& name : cameras) {
      RenderRequest request;
      request.rgb = !args.depth;
      request.depth = args.depth;
      request.width = args.width;
      request.height = args.height;
      for (const auto& stream : scenario.cameras) {  // the scenario's size unless --width/--height say otherwise
        if (stream.name == name && args.width == 0 && args.height == 0) {
          request.width = stream.width;
          request.height = stream.height;
        }
      }
      model->camera(name);  // names the cameras of the scene when unknown
      requests.push_back(request);
    }
    runner::StageMirror mirror(model);
    mirror.pose(snapshot, /*force_screen=*/true);
    Renderer renderer(model, sized_for(options, *model, cameras, requests));
    for (std::size_t i = 0; i < cameras.size(); ++i) frames.push_back(renderer.render(mirror.stage(), cameras[i], requests[i]));
    gl_renderer = renderer.gl_renderer();
  });
  for (const auto& frame : frames) write_png(frame, args.depth, output_for(args, frame.camera), gl_renderer, ", " + context);
}

nlohmann::json camera_json(const Stage& stage, const CameraSpec& spec) {
  const Eigen::Isometry3d pose = stage.camera_pose(spec.name);
  const Eigen::Quaterniond q(pose.linear());
  auto intrinsics = [](const CameraIntrinsics& k) {
    return nlohmann::json{{"width", k.width}, {"height", k.height}, {"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx},
                          {"cy", k.cy}};
  };
  return {{"name", spec.name},
          {"description", spec.description},
          {"color", intrinsics(spec.color)},
          {"depth", intrinsics(spec.depth)},
          {"on_robot", spec.on_robot},
          {"frame", "sandtray"},
          {"optical_position_m", {pose.translation().x(), pose.translation().y(), pose.translation().z()}},
          {"optical_quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

void print_cameras(SceneKind scene, bool json) {
  StageConfig config;
  config.scene = scene;
  const Stage stage(StageModel::create(config));
  nlohmann::json all = nlohmann::json::array();
  for (const auto& spec : stage.model().cameras()) all.push_back(camera_json(stage, spec));
  if (json) {
    std::cout << all.dump(2) << "\n";
    return;
  }
  std::cout << fmt::format("{:<14} {:>9} {:>8} {:>8} {:>8} {:>8}  {:<26} {}\n", "camera", "size", "fx", "fy", "cx",
                           "cy", "optical origin (sandtray)", "optical quaternion xyzw");
  for (const auto& c : all) {
    const auto& k = c["color"];
    const auto& p = c["optical_position_m"];
    const auto& q = c["optical_quaternion_xyzw"];
    std::cout << fmt::format("{:<14} {:>9} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f}  ({:+.3f}, {:+.3f}, {:+.3f})    "
                             "({:+.3f}, {:+.3f}, {:+.3f}, {:+.3f})\n",
                             c["name"].get<std::string>(),
                             fmt::format("{}x{}", k["width"].get<int>(), k["height"].get<int>()),
                             k["fx"].get<double>(), k["fy"].get<double>(), k["cx"].get<double>(),
                             k["cy"].get<double>(), p[0].get<double>(), p[1].get<double>(), p[2].get<double>(),
                             q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
  }
}

void run_render(const RenderArgs& args) {
  const SceneKind scene = scene_kind_from_name(args.scene);
  if (args.list) {
    print_cameras(scene, false);
    return;
  }
  if (!args.moment.scenario.empty()) {
    render_scenario_moment(args);
    return;
  }
  if (args.moment.time || !args.moment.overrides.empty()) {
    throw InputError("--time and --set need a scenario", args.moment.time ? "--time" : "--set", "--scenario FILE");
  }
  if (args.cameras.empty()) throw InputError("missing --camera (or use --list-cameras)", "--camera");
  if (args.cameras.size() > 1) throw InputError("one camera at a time without --scenario", "--camera", "one name");
  if (args.out.empty()) throw InputError("missing --out FILE.png", "--out");
  const std::string& camera = args.cameras.front();
  RendererOptions options;
  options.backend = args.gl.empty() ? default_gl_backend() : gl_backend_from_name(args.gl);
  options.preset = visual_preset_from_name(args.preset);
  StageConfig config;
  config.scene = scene;
  config.child_age_years = args.age;
  auto model = StageModel::create(config);
  model->camera(camera);  // validates the name before any GL work
  Stage stage(model);
  // The live game screen: free play with the items spread over the map (or left in the stash), from --seed.
  sim::Sandtray tray(std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default()), {},
                     Rng(SeedSequence(args.seed.value_or(1)).seed_for("sandtray")));
  tray.signal(sim::Signal::StartFreeplay);
  if (!args.stash) tray.signal(sim::Signal::ShuffleItems);
  tray.step(2.0);
  stage.set_screen_image(tray.render_screen(config.screen_texture_width));
  stage.update_kinematics();
  Renderer renderer(model, options);
  RenderRequest request;
  request.rgb = !args.depth;
  request.depth = args.depth;
  request.width = args.width;
  request.height = args.height;
  const FramePack frame = renderer.render(stage, camera, request);
  write_png(frame, args.depth, args.out, renderer.gl_renderer(), "");
}

const RegisterCommand register_render(60, [](CLI::App& program) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = program.add_subcommand("render", "Render one camera of the 3-D stage (off-screen) to a PNG");
  auto* scene = cmd->add_option("--scene", args->scene, "child-child or child-robot (the NAO replaces the yellow child)")
                    ->capture_default_str();
  cmd->add_option("--camera", args->cameras,
                  fmt::format("{}, {} (child-robot), {}; with --scenario: repeatable, default the scenario's cameras",
                              fmt::join(stage::kRoomCameraNames, ", "), fmt::join(stage::kNaoCameraNames, ", "),
                              stage::kTopViewCameraName));
  cmd->add_flag("--depth", args->depth, "Write the depth image: 16-bit grey PNG in millimetres (0 = none)");
  auto* preset = cmd->add_option("--preset", args->preset, "fast (no MSAA/shadows/reflections/skybox) or pretty "
                                                           "(default: fast, or the scenario's rendering.preset)");
  cmd->add_option("--width", args->width, "Image width (px; default: the camera's); intrinsics scale with it");
  cmd->add_option("--height", args->height, "Image height (px; default: the camera's)");
  auto* age = cmd->add_option("--age", args->age, "Children's age in years (4–8)")->capture_default_str();
  cmd->add_option("--gl", args->gl, "osmesa or egl (default: $MUJOCO_GL, else osmesa)");
  cmd->add_option("--out", args->out, "Output PNG (written atomically); {camera} is replaced by the camera name");
  cmd->add_option("--seed", args->seed,
                  "Seed of the sandtray game shown on the screen (default 1); with --scenario: the episode's seed "
                  "(default: the scenario's episode 0)");
  cmd->add_flag("--stash", args->stash, "Leave the items in the stash (as at the start of free play)");
  cmd->add_flag("--list-cameras", args->list, "List the cameras with resolution, intrinsics and sandtray pose");
  add_moment_options(*cmd, args->moment);
  cmd->callback([args, scene, preset, age] {
    args->scene_given = scene->count() > 0;
    args->preset_given = preset->count() > 0;
    args->age_given = age->count() > 0;
    run_render(*args);
  });
});

const RegisterLister register_cameras("cameras", "Cameras of the 3-D stage (child-robot scene): intrinsics, poses",
                                      [](bool json) { print_cameras(SceneKind::child_robot, json); });

}  // namespace
}  // namespace freeplay::cli
