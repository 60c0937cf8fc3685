#include "freeplay/ros/localisation_node.hpp"

#include <spdlog/spdlog.h>


#include "freeplay/localisation/nao_view.hpp"
#include "freeplay/runner/camera_rig.hpp"

namespace freeplay::ros_live {
namespace {

ros_graph::Transform transform(const std::string& parent, const std::string& child, const Eigen::Vector3d& t,
                               const Eigen::Quaterniond& q) {
  return {parent, child, {t.x(), t.y(), t.z()}, {q.x(), q.y(), q.z(), q.w()}};
}

}  // namespace

/// The simulated NAO's world: a stage mirroring the episode and the renderer of its head camera.
struct ServedLocalisation::Stage {
  std::unique_ptr<runner::StageMirror> mirror;
  std::unique_ptr<stage::Renderer> renderer;
};

ServedLocalisation::ServedLocalisation(localisation::LocaliserSettings settings, stage::RendererOptions renderer)
    : localiser_(std::move(settings)), renderer_options_(renderer) {}

ServedLocalisation::~ServedLocalisation() = default;

const stage::Stage* ServedLocalisation::stage() const { return stage_ ? &stage_->mirror->stage() : nullptr; }

bool ServedLocalisation::on_signal(const std::string& name, double t) {
  if (name != kLocalisingSignal) return false;
  display_.on_signal(t);
  localiser_.on_signal(t);
  return true;
}

std::vector<std::string> ServedLocalisation::observe(const runner::EpisodeSnapshot& snapshot,
                                                     std::vector<ros_graph::Transform>& frames) {
  if (snapshot.robot == nullptr) return {};
  const bool show = display_.showing(snapshot.t);
  if ((show || localiser_.looking() || localiser_.odom_T_sandtray()) && stage_ == nullptr) {
    auto model = stage::StageModel::create(runner::stage_config_for(snapshot));
    stage_ = std::make_unique<Stage>();
    stage_->mirror = std::make_unique<runner::StageMirror>(model);
    stage::RendererOptions options = renderer_options_;
    const auto& k = model->camera(localisation::kNaoLocalisationCamera).color;
    options.max_width = k.width;
    options.max_height = k.height;
    stage_->renderer = std::make_unique<stage::Renderer>(model, options);
  }
  if (stage_ == nullptr) return localiser_.take_speech();
  const bool toggled = show != markers_on_screen_;
  if (toggled) {
    markers_on_screen_ = show;
    spdlog::info("sandtray: fiducial markers {}", show ? "shown" : "hidden");
    stage_->mirror->set_screen_overlay(show ? [](cv::Mat& bgr) { localisation::draw_marker_field(bgr); }
                                            : std::function<void(cv::Mat&)>{});
  }
  const bool looking = localiser_.looking();
  stage_->mirror->pose(snapshot, false, looking || show || toggled);
  if (looking) {
    const auto view = localisation::nao_camera_view(*stage_->renderer, stage_->mirror->stage());
    if (localiser_.on_frame(snapshot.t, view.image, view.camera, view.odom_T_camera)) {
      const auto e = localisation::pose_error(*localiser_.odom_T_sandtray(), view.odom_T_sandtray_truth);
      spdlog::info("localisation: odom->sandtray off the simulator's ground truth by {:.2f} mm, {:.3f} deg",
                   e.translation_m * 1000, e.rotation_deg);
    }
  } else {
    localiser_.tick(snapshot.t);
  }
  if (const auto& odom_T_sandtray = localiser_.odom_T_sandtray()) {
    frames.push_back(transform("odom", "sandtray", odom_T_sandtray->translation(),
                               Eigen::Quaterniond(odom_T_sandtray->linear()).normalized()));
    const auto reach = localiser_.arm_reach(localisation::odom_T_shoulder(stage_->mirror->stage()));
    publishes_arm_reach_ = reach.has_value();
    if (reach) frames.push_back(transform("sandtray", "arm_reach", reach->translation, reach->rotation));
  }
  return localiser_.take_speech();
}

}  // namespace freeplay::ros_live
