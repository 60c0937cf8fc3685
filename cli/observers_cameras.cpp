// The camera rig of `freeplay run/suite`: renders the scenario's cameras when something consumes the frames
// (a camera with `video: true`, or the recorder's frame sinks).
#include <algorithm>

#include "episode_observers.hpp"
#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/runner/video_writer.hpp"

namespace freeplay::cli {

void add_camera_observers(const scenario::Scenario& scenario, const std::filesystem::path& run_dir,
                          const ObserverOptions& /*options*/, runner::EpisodeObservers& observers,
                          const std::vector<runner::FrameSink*>& frame_sinks) {
  if (scenario.cameras.empty()) return;
  std::vector<runner::FrameSink*> sinks = frame_sinks;
  const bool any_video =
      std::any_of(scenario.cameras.begin(), scenario.cameras.end(), [](const auto& c) { return c.video; });
  std::unique_ptr<runner::VideoFileSink> videos;
  if (any_video) {
    videos = std::make_unique<runner::VideoFileSink>(scenario, run_dir);
    sinks.push_back(videos.get());
  }
  if (sinks.empty()) return;  // nothing would consume the frames: cameras cost nothing
  observers.push_back(
      std::make_unique<runner::CameraRig>(scenario, runner::renderer_options(scenario.rendering), std::move(sinks)));
  if (videos != nullptr) observers.push_back(std::move(videos));
}

}  // namespace freeplay::cli
