#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/episode_capture.hpp"
#include "freeplay/runner/video_writer.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "../scratch_dir.hpp"

using namespace freeplay;
using namespace freeplay::runner;
using namespace freeplay::scenario;

namespace {

const SharedModels& models() { return SharedModels::shipped(); }

// The brief's short protocol: greeting 2 s, tutorial 2 s, free play up to 20 s, debriefing 2 s.
Scenario short_scenario(const std::string& condition, const std::string& cameras, double cap = 20.0) {
  const std::string text = fmt::format(
      "name: t\ncondition: {}\nprotocol: {{greeting_s: 2, tutorial_s: 2, freeplay_cap_s: {}, debriefing_s: 2}}\n"
      "cameras: {}\n",
      condition, cap, cameras);
  return scenario_from_document(parse_yaml(text, "test.yaml"));
}

struct KeptFrame {
  std::string camera;
  double stamp = 0;
  cv::Size rgb;
  cv::Size depth;
  cv::Mat depth_m;
  cv::Mat rgb_image;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  stage::CameraIntrinsics K_depth;
};

// Keeps what it is handed.
struct CollectingSink final : FrameSink {
  std::vector<KeptFrame> frames;
  std::string gl_renderer;
  int gl_told = 0;
  bool keep_images = false;
  void write(const stage::FramePack& f) override {
    EXPECT_EQ(gl_told, 1) << "the GL renderer is told before the first frame";
    KeptFrame kept{f.camera, f.stamp, f.rgb.size(), f.depth_m.size(), {}, {}, f.sandtray_T_camera_optical, f.K_depth};
    if (keep_images) {
      kept.depth_m = f.depth_m.clone();
      kept.rgb_image = f.rgb.clone();
    }
    frames.push_back(std::move(kept));
  }
  void set_gl_renderer(const std::string& renderer) override {
    gl_renderer = renderer;
    ++gl_told;
  }
};

// Raises the stop flag after `ticks` snapshots.
struct StopAfter final : EpisodeObserver {
  StopAfter(std::atomic<bool>& stop, int ticks) : stop_(stop), left_(ticks) {}
  void observe(const EpisodeSnapshot&) override {
    if (--left_ <= 0) stop_.store(true);
  }
  std::atomic<bool>& stop_;
  int left_;
};

/// A scratch folder for this file's test `name`.
std::filesystem::path fresh_dir(const std::string& name) { return test_support::fresh_dir("cameras-" + name); }

stage::RendererOptions osmesa() {
  stage::RendererOptions options;
  options.backend = stage::GlBackend::osmesa;
  return options;
}

std::string schema_error(const std::string& text) {
  try {
    scenario_from_document(parse_yaml(text, "test.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(CameraRig, FramesArriveAtTheirRatesWithoutChangingTheEpisode) {
  const auto s = short_scenario("child-robot",
                                "[{name: env_camera, rate_hz: 5, width: 160, height: 90, depth: true},"
                                " {name: camera_purple, rate_hz: 2, width: 96, height: 54}]");
  const std::atomic<bool> stop{false};
  const auto plain = run_episode({.scenario = s, .seed = 11, .models = models(), .stop = stop});
  CollectingSink sink;
  EpisodeObservers observers;
  observers.push_back(std::make_unique<CameraRig>(s, osmesa(), std::vector<FrameSink*>{&sink}));
  const auto* rig = static_cast<const CameraRig*>(observers.back().get());
  const auto filmed =
      run_episode({.scenario = s, .seed = 11, .models = models(), .stop = stop, .id = "t-0"}, observed_by(observers));
  EXPECT_EQ(plain.events.to_jsonl(), filmed.events.to_jsonl()) << "rendering never changes the episode";
  EXPECT_DOUBLE_EQ(plain.simulated_s, filmed.simulated_s);

  std::map<std::string, std::vector<const KeptFrame*>> by_camera;
  for (const auto& f : sink.frames) by_camera[f.camera].push_back(&f);
  ASSERT_EQ(by_camera.size(), 2u);
  const double simulated = filmed.simulated_s;
  for (const auto& camera : s.cameras) {
    const auto& frames = by_camera[camera.name];
    EXPECT_NEAR(static_cast<double>(frames.size()), camera.rate_hz * simulated, 1.0) << camera.name;
    for (std::size_t i = 1; i < frames.size(); ++i) EXPECT_GT(frames[i]->stamp, frames[i - 1]->stamp);
    EXPECT_LE(frames.back()->stamp, simulated + 1e-9);
    for (const auto* f : frames) {
      EXPECT_EQ(f->rgb, cv::Size(camera.width, camera.height)) << camera.name;
      EXPECT_EQ(f->depth.empty(), !camera.depth) << camera.name << ": depth only when asked";
    }
    EXPECT_EQ(filmed.record["cameras"]["frames"][camera.name].get<std::int64_t>(),
              static_cast<std::int64_t>(frames.size()));
    EXPECT_TRUE(filmed.record["cameras"]["wall_render_s"][camera.name].is_number());
  }
  EXPECT_EQ(by_camera["env_camera"].front()->depth, cv::Size(160, 90)) << "the Kinect's depth follows its colour";
  EXPECT_EQ(rig->frames()[0], static_cast<std::int64_t>(by_camera["env_camera"].size()));
  EXPECT_FALSE(sink.gl_renderer.empty());
  EXPECT_EQ(filmed.record["gl_renderer"].get<std::string>(), sink.gl_renderer);
  // Apart from what the rig adds, the record is the plain one (wall_s aside).
  auto a = plain.record;
  auto b = filmed.record;
  for (auto* r : {&a, &b}) {
    r->erase("wall_s");
    r->erase("gl_renderer");
    r->erase("cameras");
  }
  EXPECT_EQ(a.dump(), b.dump());  // as text: a NaN metric (no response to measure) never equals itself
}

TEST(CameraRig, DepthIsMetricAtTheScreen) {
  const auto s = short_scenario("child-robot", "[{name: env_camera, rate_hz: 1, width: 160, height: 90, depth: true}]",
                                5.0);
  CollectingSink sink;
  sink.keep_images = true;
  EpisodeObservers observers;
  observers.push_back(std::make_unique<CameraRig>(s, osmesa(), std::vector<FrameSink*>{&sink}));
  const std::atomic<bool> stop{false};
  run_episode({.scenario = s, .seed = 3, .models = models(), .stop = stop, .id = "t-0"}, observed_by(observers));
  ASSERT_FALSE(sink.frames.empty());
  const KeptFrame& f = sink.frames.front();  // greeting: blank screen, hands at rest
  // The screen centre seen by the camera: its planar depth is its z in the optical frame.
  const Eigen::Vector3d centre(0.300, -0.1675, 0.0);
  const Eigen::Vector3d in_camera = f.pose.inverse() * centre;
  ASSERT_GT(in_camera.z(), 0.0);
  const int u = static_cast<int>(std::lround(f.K_depth.fx * in_camera.x() / in_camera.z() + f.K_depth.cx));
  const int v = static_cast<int>(std::lround(f.K_depth.fy * in_camera.y() / in_camera.z() + f.K_depth.cy));
  ASSERT_TRUE(u >= 0 && v >= 0 && u < f.depth_m.cols && v < f.depth_m.rows) << u << "," << v;
  EXPECT_NEAR(f.depth_m.at<float>(v, u), in_camera.z(), 0.01) << "metres, ±1 cm";
}

TEST(StageMirror, ScreenFollowsTheGameAtMostFourTimesPerSecond) {
  sim::Sandtray tray(models().catalogue, {}, Rng(SeedSequence(4).seed_for("sandtray")));
  tray.signal(sim::Signal::StartFreeplay);
  tray.signal(sim::Signal::ShuffleItems);
  tray.step(4.0);  // the shuffled items come to rest
  std::vector<ChildSnapshot> children(1);
  children[0].seat = "purple";
  children[0].gaze_point = Eigen::Vector3d(0.3, -0.17, 0.0);
  EpisodeSnapshot snapshot;
  snapshot.t = tray.time();
  snapshot.stage = "freeplay";
  snapshot.tray = &tray;
  snapshot.children = children;
  auto model = stage::StageModel::create(stage_config_for(snapshot));
  StageMirror mirror(model);
  stage::RendererOptions options = osmesa();
  options.max_width = 200;
  options.max_height = 150;
  stage::Renderer renderer(model, options);
  stage::RenderRequest request;
  request.width = 200;
  request.height = 150;
  mirror.pose(snapshot);
  EXPECT_EQ(mirror.screen_updates(), 1);
  const cv::Mat before = renderer.render(mirror.stage(), "top_view", request).rgb.clone();

  // Nothing changed: no new texture, same image.
  tray.step(0.5);
  snapshot.t = tray.time();
  mirror.pose(snapshot);
  EXPECT_EQ(mirror.screen_updates(), 1);
  EXPECT_EQ(cv::norm(before, renderer.render(mirror.stage(), "top_view", request).rgb, cv::NORM_L1), 0.0);

  // Move the top item across the screen: the texture changes, but not sooner than 0.25 s after the last check.
  const auto items = tray.items();
  const auto& item = items.front();
  const Vec2 target(item.pose.x < 0.25 ? 0.4 : 0.1, item.pose.y < -0.17 ? -0.08 : -0.26);
  tray.place_item(item.name, Pose2{target.x(), target.y(), 0.0});
  tray.step(0.1);
  snapshot.t = tray.time();
  mirror.pose(snapshot);
  EXPECT_EQ(mirror.screen_updates(), 1) << "0.1 s after the last check";
  tray.step(0.2);
  snapshot.t = tray.time();
  mirror.pose(snapshot);
  EXPECT_EQ(mirror.screen_updates(), 2);
  const cv::Mat after = renderer.render(mirror.stage(), "top_view", request).rgb;
  EXPECT_GT(cv::norm(before, after, cv::NORM_L1) / static_cast<double>(before.total()), 0.1)
      << "the screen region shows the move";
}

TEST(VideoFileSink, WritesOneMp4PerVideoCameraWithEveryFrame) {
  const auto s = short_scenario("child-child",
                                "[{name: env_camera, rate_hz: 5, width: 160, height: 90, video: true},"
                                " {name: camera_yellow, rate_hz: 2, width: 64, height: 48}]",
                                4.0);
  const auto dir = fresh_dir("video");
  EpisodeObservers observers;
  auto videos = std::make_unique<VideoFileSink>(s, dir);
  CollectingSink counted;
  observers.push_back(std::make_unique<CameraRig>(s, osmesa(), std::vector<FrameSink*>{videos.get(), &counted}));
  observers.push_back(std::move(videos));
  const std::atomic<bool> stop{false};
  const auto result =
      run_episode({.scenario = s, .seed = 2, .models = models(), .stop = stop, .id = "t-0003"}, observed_by(observers));
  const auto path = dir / "videos" / "t-0003" / "env_camera.mp4";
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(dir / "videos" / "t-0003" / "env_camera.partial.mp4"));
  EXPECT_FALSE(std::filesystem::exists(dir / "videos" / "t-0003" / "camera_yellow.mp4")) << "video: false";
  EXPECT_EQ(result.record["cameras"]["videos"]["env_camera"].get<std::string>(), "videos/t-0003/env_camera.mp4");
  cv::VideoCapture capture(path.string());
  ASSERT_TRUE(capture.isOpened());
  int read = 0;
  cv::Mat image;
  while (capture.read(image)) {
    EXPECT_EQ(image.size(), cv::Size(160, 90));
    ++read;
  }
  EXPECT_EQ(read, result.record["cameras"]["frames"]["env_camera"].get<int>());
  EXPECT_NEAR(capture.get(cv::CAP_PROP_FPS), 5.0, 1e-6);
  std::filesystem::remove_all(dir);
}

TEST(VideoFileSink, AnAbortedEpisodeLeavesNoVideo) {
  const auto s = short_scenario("child-child", "[{name: env_camera, rate_hz: 5, width: 64, height: 48, video: true}]");
  const auto dir = fresh_dir("abort");
  std::atomic<bool> stop{false};
  EpisodeObservers observers;
  auto videos = std::make_unique<VideoFileSink>(s, dir);
  observers.push_back(std::make_unique<CameraRig>(s, osmesa(), std::vector<FrameSink*>{videos.get()}));
  observers.push_back(std::move(videos));
  observers.push_back(std::make_unique<StopAfter>(stop, 30));
  const auto result =
      run_episode({.scenario = s, .seed = 2, .models = models(), .stop = stop, .id = "t-0"}, observed_by(observers));
  EXPECT_TRUE(result.aborted);
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    EXPECT_FALSE(entry.is_regular_file()) << "left behind: " << entry.path();
  }
  std::filesystem::remove_all(dir);
}

TEST(EpisodeCapture, StopsAtTheFirstTickAtOrAfterTheMoment) {
  const auto s = short_scenario("child-robot", "[]", 30.0);
  int calls = 0;
  std::string stage;
  double freeplay_t = -1;
  const auto at = capture_episode_moment(s, 5, models(), {"freeplay", 3.04}, [&](const EpisodeSnapshot& snapshot) {
    ++calls;
    stage = std::string(snapshot.stage);
    freeplay_t = snapshot.freeplay_t;
  });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(stage, "freeplay");
  EXPECT_NEAR(at.stage_t, 3.1, 1e-6);
  EXPECT_NEAR(freeplay_t, 3.1, 1e-6);
  EXPECT_NEAR(at.t, 4.0 + 3.1, 1e-6);
  const auto tutorial = capture_episode_moment(s, 5, models(), {"tutorial", 1.0}, [](const EpisodeSnapshot& snapshot) {
    EXPECT_EQ(snapshot.stage, "tutorial");
  });
  EXPECT_NEAR(tutorial.t, 3.0, 1e-6);
}

TEST(EpisodeCapture, MomentsBeyondTheStageAreClearErrors) {
  const auto s = short_scenario("child-robot", "[]", 30.0);
  auto message = [&](const EpisodeMoment& moment) {
    try {
      capture_episode_moment(s, 5, models(), moment, [](const EpisodeSnapshot&) {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({"freeplay", 31}).find("free play stops at its cap of 30 s"), std::string::npos);
  EXPECT_NE(message({"greeting", 2.5}).find("the greeting lasts 2 s"), std::string::npos);
  EXPECT_NE(message({"lunch", 1}).find("greeting, tutorial, freeplay, debriefing"), std::string::npos);
  EXPECT_NE(message({"freeplay", -1}).find("--time"), std::string::npos);
}

TEST(EpisodeCapture, SaysWhenTheChildrenQuitBeforeTheMoment) {
  // A child with no attention span quits early; the moment lies after the quit.
  const auto s = scenario_from_document(parse_yaml(
      "name: t\ncondition: child-robot\nchildren: {purple: {attention_span: 0, sociability: 0}}\n"
      "protocol: {greeting_s: 0, tutorial_s: 0, freeplay_cap_s: 2400, debriefing_s: 0}\n",
      "test.yaml"));
  std::string message = "no error";
  try {
    capture_episode_moment(s, 5, models(), {"freeplay", 2399}, [](const EpisodeSnapshot&) {});
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("the episode ended at "), std::string::npos) << message;
  EXPECT_NE(message.find(" s of free play (children quit)"), std::string::npos) << message;
}

TEST(CameraSchema, BadRenderingAndCameraValuesNameTheAllowedValues) {
  const std::string head = "name: x\ncondition: child-robot\n";
  auto msg = schema_error(head + "rendering: {backend: vulkan}\n");
  EXPECT_NE(msg.find("'rendering.backend'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("osmesa, egl"), std::string::npos) << msg;
  msg = schema_error(head + "rendering: {preset: ugly}\n");
  EXPECT_NE(msg.find("fast, pretty"), std::string::npos) << msg;
  msg = schema_error(head + "cameras: [{name: env_camera, video: maybe}]\n");
  EXPECT_NE(msg.find("'cameras[0].video'"), std::string::npos) << msg;
  msg = schema_error(head + "cameras: [{name: env_camera}, {name: env_camera}]\n");
  EXPECT_NE(msg.find("listed twice"), std::string::npos) << msg;
  msg = schema_error("name: x\ncondition: child-child\ncameras: [{name: CameraTop}]\n");
  EXPECT_NE(msg.find("test.yaml:3:18"), std::string::npos) << msg;
  EXPECT_NE(msg.find("absent in child-child"), std::string::npos) << msg;
  const auto s = scenario_from_document(
      parse_yaml(head + "rendering: {backend: egl, preset: pretty}\ncameras: [{name: env_camera, video: true}]\n",
                 "test.yaml"));
  EXPECT_EQ(s.rendering.backend, stage::GlBackend::egl);
  EXPECT_EQ(s.rendering.preset, stage::VisualPreset::pretty);
  EXPECT_TRUE(s.cameras.at(0).video);
  const auto defaults = scenario_from_document(parse_yaml(head + "cameras: [{name: env_camera}]\n", "test.yaml"));
  EXPECT_EQ(defaults.rendering.backend, std::nullopt);
  EXPECT_EQ(defaults.rendering.preset, stage::VisualPreset::fast);
  EXPECT_FALSE(defaults.cameras.at(0).video);
}

// The renderer takes the scenario's typed backend and preset; $MUJOCO_GL (else OSMesa) is read only when `rendering`
// names no backend, so a bad $MUJOCO_GL does not matter to a scenario that names one.
TEST(CameraRig, RendererOptionsTakeTheScenariosBackendElseMujocoGl) {
  const char* before = std::getenv("MUJOCO_GL");
  const std::optional<std::string> saved = before != nullptr ? std::optional<std::string>(before) : std::nullopt;
  stage::RenderingSettings named;
  named.backend = stage::GlBackend::egl;
  named.preset = stage::VisualPreset::pretty;
  setenv("MUJOCO_GL", "vulkan", 1);
  const auto options = renderer_options(named);
  EXPECT_EQ(options.backend, stage::GlBackend::egl);
  EXPECT_EQ(options.preset, stage::VisualPreset::pretty);
  EXPECT_THROW(renderer_options(stage::RenderingSettings{}), InputError);  // unnamed: $MUJOCO_GL is read
  setenv("MUJOCO_GL", "egl", 1);
  EXPECT_EQ(renderer_options(stage::RenderingSettings{}).backend, stage::GlBackend::egl);
  unsetenv("MUJOCO_GL");
  EXPECT_EQ(renderer_options(stage::RenderingSettings{}).backend, stage::GlBackend::osmesa);
  EXPECT_EQ(renderer_options(stage::RenderingSettings{}).preset, stage::kDefaultVisualPreset);
  if (saved) setenv("MUJOCO_GL", saved->c_str(), 1);
}
