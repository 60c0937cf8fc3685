// Google Benchmark programs for the stage. Targets (issue): dynamic NAO scene ≥ 10 000 mj_step/s on one core;
// kinematic update of the whole stage ≤ 20 µs; `fast` preset ≥ 40 frames/s per camera at 960×540 with RGB
// read-back; peak memory of one rendering worker ≤ 300 MB (reported as the peak_rss_MB counter).

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <array>

#include "freeplay/stage/avatar_controller.hpp"
#include "freeplay/stage/nao_controller.hpp"
#include "freeplay/stage/renderer.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

std::shared_ptr<const StageModel> model_for(SceneKind scene) {
  StageConfig config;
  config.scene = scene;
  return StageModel::create(config);
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// Raw mj_step of the child-robot scene (NAO with 25 position servos, one seated child), one thread.
void BM_MjStepDynamicNaoScene(benchmark::State& state) {
  Stage stage(model_for(SceneKind::child_robot), StageMode::dynamic);
  NaoController nao(stage);
  nao.point_at({0.22, -0.04});
  const mjModel* m = raw_model(stage.model());
  mjData* d = raw_data(stage);
  for (auto _ : state) {
    mj_step(m, d);
    benchmark::DoNotOptimize(d->qacc[0]);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MjStepDynamicNaoScene);

// Stage::step: mj_step plus holding the avatar joints and refreshing poses (what controller tests call).
void BM_StageStepDynamic(benchmark::State& state) {
  Stage stage(model_for(SceneKind::child_robot), StageMode::dynamic);
  for (auto _ : state) stage.step(1);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_StageStepDynamic);

// Kinematic update of the whole stage: every body, site and camera pose from the joint angles.
void BM_KinematicStageUpdate(benchmark::State& state) {
  Stage stage(model_for(state.range(0) == 0 ? SceneKind::child_child : SceneKind::child_robot));
  for (auto _ : state) {
    raw_data(stage)->qpos[0] += 1e-9;
    stage.update_kinematics();
    benchmark::DoNotOptimize(raw_data(stage)->xpos[3]);
  }
}
BENCHMARK(BM_KinematicStageUpdate)->Arg(0)->Arg(1)->ArgName("child_robot");

// Kinematic tick of a policy suite: NAO gaze + one avatar's gaze and touch + the pose update.
void BM_KinematicControlTick(benchmark::State& state) {
  Stage stage(model_for(SceneKind::child_robot));
  NaoController nao(stage);
  AvatarController child(stage, ChildRole::purple);
  double x = 0.2;
  for (auto _ : state) {
    x = x > 0.4 ? 0.2 : x + 0.001;
    nao.look_at({x, -0.2, 0.0});
    child.look_at({x, -0.2, 0.0});
    child.touch({x, -0.25});
    stage.update_kinematics();
  }
}
BENCHMARK(BM_KinematicControlTick);

// NAO pointing IK (damped least squares on the arm chain) for a target stepping 2 mm along x from `from` to `to`
// at y, then back to `from`.
void point_along(benchmark::State& state, double from, double to, double y) {
  Stage stage(model_for(SceneKind::child_robot));
  NaoController nao(stage);
  double x = from;
  for (auto _ : state) {
    x = x > to ? from : x + 0.002;
    benchmark::DoNotOptimize(nao.point_at({x, y}));
  }
}

// Targets within reach near the robot's edge.
void BM_NaoPointAt(benchmark::State& state) { point_along(state, 0.15, 0.28, -0.03); }
BENCHMARK(BM_NaoPointAt);

// Targets beyond the whole arm's length (far side of the screen), as most finger poses of a social episode: one
// solve from the default pointing pose, stretching the arm towards the target.
void BM_NaoPointAtOutOfReach(benchmark::State& state) { point_along(state, 0.45, 0.58, -0.3); }
BENCHMARK(BM_NaoPointAtOutOfReach);

// `fast` preset frames per second for one camera at its native resolution, RGB read back into a cv::Mat.
void BM_RenderFast(benchmark::State& state) {
  static const std::array<const char*, 4> kCameras = {"camera_purple", "camera_yellow", "env_camera", "CameraTop"};
  const char* camera = kCameras[static_cast<size_t>(state.range(0))];
  state.SetLabel(camera);
  const auto model = model_for(SceneKind::child_robot);
  Stage stage(model);
  stage.set_screen_image(demo_screen_image());
  Renderer renderer(model, {GlBackend::osmesa, VisualPreset::fast, 960, 540});
  for (auto _ : state) {
    const FramePack frame = renderer.render(stage, camera);
    benchmark::DoNotOptimize(frame.rgb.data);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["peak_rss_MB"] = peak_rss_mb();
}
BENCHMARK(BM_RenderFast)->DenseRange(0, 3)->UseRealTime()->Unit(benchmark::kMillisecond);

// Same with the depth image converted to metres as well.
void BM_RenderFastWithDepth(benchmark::State& state) {
  const auto model = model_for(SceneKind::child_robot);
  Stage stage(model);
  Renderer renderer(model, {GlBackend::osmesa, VisualPreset::fast, 960, 540});
  RenderRequest request;
  request.depth = true;
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(stage, "env_camera", request).depth_m.data);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RenderFastWithDepth)->UseRealTime()->Unit(benchmark::kMillisecond);

// The live screen picture changing every frame (texture upload included).
void BM_RenderFastWithScreenUpdate(benchmark::State& state) {
  const auto model = model_for(SceneKind::child_robot);
  Stage stage(model);
  Renderer renderer(model, {GlBackend::osmesa, VisualPreset::fast, 960, 540});
  const cv::Mat image = demo_screen_image(1920, 1080);
  for (auto _ : state) {
    stage.set_screen_image(image);
    benchmark::DoNotOptimize(renderer.render(stage, "env_camera").rgb.data);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RenderFastWithScreenUpdate)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace freeplay::stage
