// Recording cost: an episode with and without the bag recorder (per simulated second), and camera frame sets at the
// real resolutions (per 1/30 s: 3 colour 960×540 JPEG q90 + 2 depth 640×480 compressedDepth PNG), with bag bytes.
#include <benchmark/benchmark.h>

#include <fmt/format.h>

#include <filesystem>

#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"

using namespace freeplay;

namespace {

const runner::SharedModels& models() { return runner::SharedModels::shipped(); }

scenario::Scenario test_scenario() {
  return scenario::scenario_from_document(parse_yaml(
      "name: bench\ncondition: child-robot\nrecord: true\n"
      "protocol: {greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 30, debriefing_s: 1}\n",
      "bench.yaml"));
}

std::filesystem::path bench_dir() {
  const auto dir = std::filesystem::temp_directory_path() / "freeplay-bench-recording";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void run(benchmark::State& state, bool record) {
  const auto s = test_scenario();
  const auto dir = bench_dir();
  double simulated = 0.0;
  std::uintmax_t bytes = 0;
  for (auto _ : state) {
    runner::EpisodeObservers observers;
    if (record) observers.push_back(std::make_unique<recording::BagRecorder>(dir / "sessions", s.recording));
    // An observer that does nothing, so that both variants tick at 10 Hz in every stage.
    struct Idle final : runner::EpisodeObserver {
      void observe(const runner::EpisodeSnapshot&) override {}
    };
    if (!record) observers.push_back(std::make_unique<Idle>());
    const std::atomic<bool> stop{false};
    const auto result =
        runner::run_episode({.scenario = s, .seed = 11, .models = models(), .stop = stop, .id = "bench-0000"},
                            runner::observed_by(observers));
    simulated += result.simulated_s;
    if (record) bytes += std::filesystem::file_size(dir / "sessions/bench-0000/freeplay.bag");
  }
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  if (record) state.counters["bag_MB_per_sim_min"] = static_cast<double>(bytes) / 1e6 / (simulated / 60.0);
}

void BM_EpisodeObserved(benchmark::State& state) { run(state, false); }
void BM_EpisodeRecorded(benchmark::State& state) { run(state, true); }

// One 1/30 s camera frame set at the real resolutions, the colour images a rendered sandtray screen (compressed on the
// recorder's default 2 encoder threads).
void BM_CameraFrameSet(benchmark::State& state) {
  const auto dir = bench_dir();
  recording::BagRecorder recorder(dir / "sessions");
  recorder.begin({nullptr, "frames-0000", 1});
  sim::Sandtray tray(models().catalogue, {}, Rng(3));
  tray.signal(sim::Signal::StartFreeplay);
  cv::Mat rgb = tray.render_screen(960);
  cv::Mat depth(480, 640, CV_32FC1);
  for (int r = 0; r < depth.rows; ++r) {
    for (int c = 0; c < depth.cols; ++c) depth.at<float>(r, c) = 0.4F + 0.0005F * static_cast<float>(r + c);
  }
  const stage::CameraIntrinsics K{960, 540, 697.811, 697.811, 479.047, 261.227};
  const stage::CameraIntrinsics K_depth{640, 480, 475.0, 475.0, 320.0, 240.0};
  double t = 0.0;
  for (auto _ : state) {
    for (const char* camera : {"camera_purple", "camera_yellow", "env_camera"}) {
      stage::FramePack f;
      f.camera = camera;
      f.stamp = t;
      f.rgb = rgb.clone();  // new pixels each time: the recorder compresses a repeated image only once
      f.K = K;
      if (std::string(camera) != "env_camera") {
        f.depth_m = depth.clone();
        f.K_depth = K_depth;
      }
      recorder.write(f);
    }
    t += 1.0 / 30.0;
  }
  runner::EpisodeResult result;
  recorder.end(result);
  const auto bytes = static_cast<double>(std::filesystem::file_size(dir / "sessions/frames-0000/freeplay.bag"));
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(t, benchmark::Counter::kIsRate);
  state.counters["bag_MB_per_sim_min"] = bytes / 1e6 / (t / 60.0);
}

// End to end: `scenarios/record-demo.yaml` (three cameras rendered by the camera rig with the fast preset, depth for
// the two SR300s, the recorder writing every stream) over a short protocol, cameras at `rate_hz`; wall-clock rate.
void record_demo(benchmark::State& state, double rate_hz) {
  const auto rate = fmt::format("{}", rate_hz);
  const auto s = scenario::load_scenario(std::string(FREEPLAY_SCENARIOS_DIR) + "/record-demo.yaml",
                                       {"protocol.greeting_s=2", "protocol.tutorial_s=2", "protocol.freeplay_cap_s=10",
                                        "protocol.debriefing_s=1", "cameras.0.rate_hz=" + rate,
                                        "cameras.1.rate_hz=" + rate, "cameras.2.rate_hz=" + rate});
  const auto dir = bench_dir();
  double simulated = 0.0;
  std::uintmax_t bytes = 0;
  for (auto _ : state) {
    runner::EpisodeObservers observers;
    auto recorder = std::make_unique<recording::BagRecorder>(dir / "sessions", s.recording);
    std::vector<runner::FrameSink*> sinks{recorder.get()};
    observers.push_back(std::move(recorder));
    observers.push_back(std::make_unique<runner::CameraRig>(s, runner::renderer_options(s.rendering), sinks));
    const std::atomic<bool> stop{false};
    const auto result =
        runner::run_episode({.scenario = s, .seed = 11, .models = models(), .stop = stop, .id = "demo-0000"},
                            runner::observed_by(observers));
    simulated += result.simulated_s;
    bytes += std::filesystem::file_size(dir / "sessions/demo-0000/freeplay.bag");
  }
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
  state.counters["bag_MB_per_sim_min"] = static_cast<double>(bytes) / 1e6 / (simulated / 60.0);
}

void BM_RecordDemoCameras30Hz(benchmark::State& state) { record_demo(state, 30.0); }
void BM_RecordDemoCameras5Hz(benchmark::State& state) { record_demo(state, 5.0); }

}  // namespace

BENCHMARK(BM_RecordDemoCameras30Hz)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_RecordDemoCameras5Hz)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_EpisodeObserved)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_EpisodeRecorded)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_CameraFrameSet)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();
