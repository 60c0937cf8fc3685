// `freeplay render`: off-screen images of the 3-D stage's cameras; `freeplay list cameras`.

#include <fmt/format.h>
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
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/stage/renderer.hpp"
#include "freeplay/stage/stage.hpp"

namespace freeplay::cli {
namespace {

using namespace freeplay::stage;

struct RenderArgs {
  std::string scene = "child-robot";
  std::string camera;
  bool depth = false;
  std::string preset = "fast";
  int width = 0;
  int height = 0;
  double age = 7.0;
  std::string gl;
  std::string out;
  bool list = false;
  std::uint64_t seed = 1;
  bool stash = false;
};

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
  if (args.camera.empty()) throw InputError("missing --camera (or use --list-cameras)", "--camera");
  if (args.out.empty()) throw InputError("missing --out FILE.png", "--out");
  RendererOptions options;
  options.backend = args.gl.empty() ? default_gl_backend() : gl_backend_from_name(args.gl);
  options.preset = visual_preset_from_name(args.preset);
  StageConfig config;
  config.scene = scene;
  config.child_age_years = args.age;
  auto model = StageModel::create(config);
  model->camera(args.camera);  // validates the name before any GL work
  Stage stage(model);
  // The live game screen: free play with the items spread over the map (or left in the stash), from --seed.
  sim::Sandtray tray(std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default()), {},
                     Rng(SeedSequence(args.seed).seed_for("sandtray")));
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
  const FramePack frame = renderer.render(stage, args.camera, request);
  cv::Mat image;
  if (args.depth) {
    frame.depth_m.convertTo(image, CV_16UC1, 1000.0);  // millimetres, saturating at 65.535 m
  } else {
    cv::cvtColor(frame.rgb, image, cv::COLOR_RGB2BGR);
  }
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) throw std::runtime_error("PNG encoding failed");
  write_file_atomically(args.out, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
  spdlog::info("wrote {} ({}x{}, camera {}, GL renderer: {})", args.out, image.cols, image.rows, frame.camera,
               renderer.gl_renderer());
}

const RegisterCommand register_render(60, [](CLI::App& program) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = program.add_subcommand("render", "Render one camera of the 3-D stage (off-screen) to a PNG");
  cmd->add_option("--scene", args->scene, "child-child or child-robot (the NAO replaces the yellow child)")
      ->capture_default_str();
  cmd->add_option("--camera", args->camera,
                  "camera_purple, camera_yellow, env_camera, CameraTop, CameraBottom (child-robot), top_view");
  cmd->add_flag("--depth", args->depth, "Write the depth image: 16-bit grey PNG in millimetres (0 = none)");
  cmd->add_option("--preset", args->preset, "fast (no MSAA/shadows/reflections/skybox) or pretty")
      ->capture_default_str();
  cmd->add_option("--width", args->width, "Image width (px; default: the camera's); intrinsics scale with it");
  cmd->add_option("--height", args->height, "Image height (px; default: the camera's)");
  cmd->add_option("--age", args->age, "Children's age in years (4–8)")->capture_default_str();
  cmd->add_option("--gl", args->gl, "osmesa or egl (default: $MUJOCO_GL, else osmesa)");
  cmd->add_option("--out", args->out, "Output PNG (written atomically)");
  cmd->add_option("--seed", args->seed, "Seed of the sandtray game shown on the screen")->capture_default_str();
  cmd->add_flag("--stash", args->stash, "Leave the items in the stash (as at the start of free play)");
  cmd->add_flag("--list-cameras", args->list, "List the cameras with resolution, intrinsics and sandtray pose");
  cmd->callback([args] { run_render(*args); });
});

const RegisterLister register_cameras("cameras", "Cameras of the 3-D stage (child-robot scene): intrinsics, poses",
                                      [](bool json) { print_cameras(SceneKind::child_robot, json); });

}  // namespace
}  // namespace freeplay::cli
