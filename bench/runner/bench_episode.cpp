// End-to-end speed of the episode loop: simulated seconds per wall second for each default scenario (no cameras),
// and the peak resident memory of the worker; then short child-robot episodes with the camera rig rendering.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>

#include "freeplay/core/memory.hpp"
#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/runner/episode.hpp"

using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

const SharedModels& models() { return SharedModels::shipped(); }

void run_scenario(benchmark::State& state, const char* file) {
  freeplay::keep_freed_memory_for_reuse();  // as the freeplay program does at start
  const auto scenario = load_scenario(std::string(FREEPLAY_SCENARIOS_DIR) + "/" + file);
  const std::atomic<bool> stop{false};
  double simulated = 0.0;
  double freeplay = 0.0;
  double wall = 0.0;
  std::uint64_t seed = 1;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const auto result = run_episode({.scenario = scenario, .seed = seed++, .models = models(), .stop = stop});
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    simulated += result.simulated_s;
    freeplay += result.duration_s;
    benchmark::DoNotOptimize(result.record);
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["sim_s_per_wall_s"] = simulated / wall;            // whole protocol
  state.counters["freeplay_s_per_wall_s"] = freeplay / wall;        // free play only
  state.counters["freeplay_min_per_episode"] = freeplay / 60.0 / static_cast<double>(state.iterations());
  state.counters["peak_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// Counts the frames it is handed (stands for a video writer or a recorder without their encoding cost).
struct CountingSink final : FrameSink {
  std::int64_t frames = 0;
  void write(const freeplay::stage::FramePack& frame) override {
    benchmark::DoNotOptimize(frame.rgb.data);
    ++frames;
  }
};

// The asocial child-robot scenario with the short protocol (greeting 2 s, tutorial 2 s, free play ≤ 20 s,
// debriefing 2 s) and `cameras`, rendered with OSMesa (or $MUJOCO_GL), preset fast.
void run_with_cameras(benchmark::State& state, const std::string& cameras) {
  const auto scenario = load_scenario(std::string(FREEPLAY_SCENARIOS_DIR) + "/child-robot-asocial.yaml",
                                      {"protocol.greeting_s=2", "protocol.tutorial_s=2", "protocol.freeplay_cap_s=20",
                                       "protocol.debriefing_s=2", "cameras=" + cameras});
  const std::atomic<bool> stop{false};
  double simulated = 0.0;
  double wall = 0.0;
  double render_wall = 0.0;
  std::int64_t frames = 0;
  std::uint64_t seed = 1;
  std::string gl_renderer;
  for (auto _ : state) {
    CountingSink sink;
    EpisodeObservers observers;
    observers.push_back(std::make_unique<CameraRig>(scenario, renderer_options(scenario.rendering),
                                                    std::vector<FrameSink*>{&sink}));
    const auto start = std::chrono::steady_clock::now();
    const auto result = run_episode(
        {.scenario = scenario, .seed = seed, .models = models(), .stop = stop, .id = "bench"}, observed_by(observers));
    ++seed;
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    simulated += result.simulated_s;
    frames += sink.frames;
    if (result.record.contains("cameras")) {
      for (const auto& [camera, seconds] : result.record["cameras"]["wall_render_s"].items()) {
        render_wall += seconds.get<double>();
      }
    }
    if (result.record["gl_renderer"].is_string()) gl_renderer = result.record["gl_renderer"].get<std::string>();
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["sim_s_per_wall_s"] = simulated / wall;
  if (!scenario.cameras.empty()) {
    state.counters["frames_per_wall_s"] = static_cast<double>(frames) / wall;
    state.counters["render_share"] = render_wall / wall;  // fraction of the wall time spent in Renderer::render
  }
  state.counters["peak_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
  state.SetLabel(gl_renderer);
}

void BM_ChildRobotAsocialShortNoCameras(benchmark::State& state) { run_with_cameras(state, "[]"); }
void BM_ChildRobotAsocialEnvCamera30Hz(benchmark::State& state) {
  run_with_cameras(state, "[{name: env_camera, rate_hz: 30, width: 960, height: 540}]");
}
void BM_ChildRobotAsocialThreeCameras30Hz(benchmark::State& state) {
  run_with_cameras(state,
                   "[{name: camera_purple, rate_hz: 30, width: 960, height: 540, depth: true},"
                   " {name: camera_yellow, rate_hz: 30, width: 960, height: 540, depth: true},"
                   " {name: env_camera, rate_hz: 30, width: 960, height: 540}]");
}

void BM_ChildChildEpisode(benchmark::State& state) { run_scenario(state, "child-child.yaml"); }
void BM_ChildRobotAsocialEpisode(benchmark::State& state) { run_scenario(state, "child-robot-asocial.yaml"); }
void BM_ChildRobotSocialEpisode(benchmark::State& state) { run_scenario(state, "child-robot-social.yaml"); }

}  // namespace

BENCHMARK(BM_ChildChildEpisode)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_ChildRobotAsocialEpisode)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_ChildRobotSocialEpisode)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_ChildRobotAsocialShortNoCameras)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ChildRobotAsocialEnvCamera30Hz)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ChildRobotAsocialThreeCameras30Hz)->Unit(benchmark::kMillisecond)->Iterations(1);
