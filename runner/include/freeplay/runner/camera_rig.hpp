#pragma once
// The stage's cameras during an episode: a kinematic 3-D stage posed from each 10 Hz snapshot (robot joints,
// children's gaze and touches, the live game screen) and rendered at each scenario camera's rate.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "freeplay/stage/avatar_controller.hpp"
#include "freeplay/stage/camera_settings.hpp"
#include "freeplay/stage/nao_controller.hpp"
#include "freeplay/stage/renderer.hpp"
#include "freeplay/stage/stage.hpp"

namespace freeplay::runner {

/// The renderer settings of a scenario's `rendering:` section ($MUJOCO_GL, else OSMesa, when no backend is named).
stage::RendererOptions renderer_options(const stage::RenderingSettings& rendering);

/// The stage model a snapshot's episode needs: its scene, and the children's mean age (one size fits both avatars).
stage::StageConfig stage_config_for(const EpisodeSnapshot& snapshot);

/// A kinematic stage that mirrors an episode: poses the NAO and the avatars and shows the game's screen.
class StageMirror {
 public:
  /// Least simulated time between two screen-texture updates (the real `/sandtray/background` is ≤ 4 Hz).
  static constexpr double kScreenPeriodS = 0.25;

  /// A stage for `model` with the NAO in StandInit (child-robot scenes) and the children at rest.
  explicit StageMirror(std::shared_ptr<const stage::StageModel> model);

  /// Copies `snapshot` onto the stage: NAO joints, avatars' gaze and right hand, and the screen picture when the
  /// game changed and `kScreenPeriodS` has passed since the last update (or at once with `force_screen`; never
  /// without `screen`, for users that only need the bodies' poses).
  void pose(const EpisodeSnapshot& snapshot, bool force_screen = false, bool screen = true);

  /// Draws `overlay` over every later screen picture (nothing: none), e.g. the marker field the game shows while the
  /// robot localises; the next `pose` with `screen` replaces the picture even when the game did not change.
  void set_screen_overlay(std::function<void(cv::Mat& bgr)> overlay);

  /// The posed stage (kinematics up to date after `pose`).
  const stage::Stage& stage() const { return stage_; }
  /// How many times the screen texture was replaced.
  int screen_updates() const { return screen_updates_; }

 private:
  void update_screen(const EpisodeSnapshot& snapshot, bool force);
  void pose_robot(const RobotSnapshot& robot);
  void pose_child(const ChildSnapshot& child);

  stage::Stage stage_;
  std::unique_ptr<stage::NaoController> nao_;
  std::vector<std::pair<std::string, stage::AvatarController>> avatars_;
  std::vector<int> joint_slots_;  // snapshot joint index → NaoJointVector index (-1: not a NAO joint)
  stage::NaoJointVector joints_{};
  std::optional<std::uint64_t> screen_signature_;
  std::function<void(cv::Mat&)> screen_overlay_;
  double screen_checked_t_ = -1e9;
  int screen_updates_ = 0;
};

/// Renders the scenario's cameras during an episode and hands every frame to its sinks; never changes the episode.
///
/// Frame k of a camera at `rate_hz` is due at k / rate_hz on the sandtray clock; at each 10 Hz tick the due frames
/// are rendered once from the tick's state and handed over with their own stamps (cameras faster than 10 Hz repeat
/// the tick's image, as the simulated world changes only at ticks). The stage model is chosen at the first
/// snapshot, when the children's ages are known.
class CameraRig final : public EpisodeObserver {
 public:
  /// A rig for `scenario.cameras` rendering with `options` into `sinks` (which must outlive the episode).
  CameraRig(const scenario::Scenario& scenario, stage::RendererOptions options, std::vector<FrameSink*> sinks);
  ~CameraRig() override;
  CameraRig(const CameraRig&) = delete;
  CameraRig& operator=(const CameraRig&) = delete;

  /// Resets the frame schedule.
  void begin(const EpisodeInfo& info) override;
  /// Poses the stage and renders the cameras whose frames are due.
  void observe(const EpisodeSnapshot& snapshot) override;
  /// Adds `gl_renderer` and `cameras` {frames, wall_render_s} to the record.
  void end(EpisodeResult& result) override;

  /// Frames handed to the sinks so far, per scenario camera (scenario order).
  const std::vector<std::int64_t>& frames() const { return frames_; }
  /// The GL renderer string (empty before the first render).
  const std::string& gl_renderer() const { return gl_renderer_; }

 private:
  void start(const EpisodeSnapshot& snapshot);

  std::vector<stage::CameraStream> cameras_;
  stage::RendererOptions options_;
  std::vector<FrameSink*> sinks_;
  std::unique_ptr<StageMirror> mirror_;
  std::unique_ptr<stage::Renderer> renderer_;
  std::string gl_renderer_;
  std::vector<std::int64_t> next_frame_;
  std::vector<std::int64_t> frames_;
  std::vector<double> wall_render_s_;
};

}  // namespace freeplay::runner
