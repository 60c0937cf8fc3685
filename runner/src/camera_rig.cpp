#include "freeplay/runner/camera_rig.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "freeplay/core/error.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::runner {

namespace {

/// FNV-1a over raw bytes, for the screen's change signature.
class SignatureHasher {
 public:
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) value_ = (value_ ^ bytes[i]) * 1099511628211ULL;
  }
  void add(double v) { add(&v, sizeof v); }
  void add(std::int64_t v) { add(&v, sizeof v); }
  std::uint64_t value() const { return value_; }

 private:
  std::uint64_t value_ = 14695981039346656037ULL;
};

/// Quantises a length to half a screen-texture pixel so resting items give a stable signature.
std::int64_t quantise(double metres, double pixels_per_metre) {
  return static_cast<std::int64_t>(std::llround(metres * pixels_per_metre * 2.0));
}

/// Everything the screen picture depends on, at texture resolution.
std::uint64_t screen_signature(const sim::Sandtray& tray, double pixels_per_metre) {
  SignatureHasher h;
  h.add(static_cast<std::int64_t>(tray.state()));
  h.add(static_cast<std::int64_t>(tray.background_version()));
  h.add(static_cast<std::int64_t>(tray.drawing_enabled()));
  h.add(tray.drawing_coverage());
  for (const auto& item : tray.items()) {
    h.add(quantise(item.pose.x, pixels_per_metre));
    h.add(quantise(item.pose.y, pixels_per_metre));
    h.add(static_cast<std::int64_t>(std::llround(item.pose.theta * 1000.0)));
    h.add(static_cast<std::int64_t>(item.z));
    h.add(static_cast<std::int64_t>(item.visible));
  }
  for (const auto& touch : tray.touches()) {
    h.add(static_cast<std::int64_t>(touch.finger));
    h.add(quantise(touch.position.x(), pixels_per_metre));
    h.add(quantise(touch.position.y(), pixels_per_metre));
  }
  if (const auto hand = tray.robot_hand()) {
    h.add(quantise(hand->x(), pixels_per_metre));
    h.add(quantise(hand->y(), pixels_per_metre));
  }
  return h.value();
}

stage::ChildRole role_of(const std::string& seat) {
  if (seat == "purple") return stage::ChildRole::purple;
  if (seat == "yellow") return stage::ChildRole::yellow;
  throw InputError("unknown seat '" + seat + "'", "seat", "purple, yellow");
}

/// The colour and depth image sizes of one scenario camera (the renderer checks both, even without depth).
std::pair<cv::Size, cv::Size> image_sizes(const stage::StageModel& model, const stage::CameraStream& camera) {
  const auto& spec = model.camera(camera.name);
  const cv::Size color(camera.width, camera.height);
  const bool depth_follows_color = spec.depth.width == spec.color.width && spec.depth.height == spec.color.height;
  return {color, depth_follows_color ? color : cv::Size(spec.depth.width, spec.depth.height)};
}

}  // namespace

stage::RendererOptions renderer_options(const stage::RenderingSettings& rendering) {
  stage::RendererOptions options;
  options.backend = rendering.backend ? *rendering.backend : stage::default_gl_backend();  // reads $MUJOCO_GL
  options.preset = rendering.preset;
  return options;
}

stage::StageConfig stage_config_for(const EpisodeSnapshot& snapshot) {
  stage::StageConfig config;
  config.scene = snapshot.robot != nullptr ? stage::SceneKind::child_robot : stage::SceneKind::child_child;
  if (!snapshot.children.empty()) {
    double sum = 0.0;
    for (const auto& child : snapshot.children) sum += child.age_years;
    config.child_age_years = std::clamp(sum / static_cast<double>(snapshot.children.size()), 4.0, 8.0);
  }
  return config;
}

// ---- StageMirror ---------------------------------------------------------------------------------------------

StageMirror::StageMirror(std::shared_ptr<const stage::StageModel> model) : stage_(std::move(model)) {
  if (stage_.model().nao().present) {
    nao_ = std::make_unique<stage::NaoController>(stage_);
    nao_->go_to_posture(stage::NaoPosture::StandInit);
    joints_ = nao_->joint_targets();
  }
  stage_.update_kinematics();
}

void StageMirror::pose(const EpisodeSnapshot& snapshot, bool force_screen, bool screen) {
  if (screen) update_screen(snapshot, force_screen);
  if (snapshot.robot != nullptr && nao_ != nullptr) pose_robot(*snapshot.robot);
  for (const auto& child : snapshot.children) pose_child(child);
  stage_.update_kinematics();
}

void StageMirror::update_screen(const EpisodeSnapshot& snapshot, bool force) {
  if (snapshot.tray == nullptr) return;
  if (!force && snapshot.t - screen_checked_t_ < kScreenPeriodS - 1e-9) return;
  const int width = stage_.model().config().screen_texture_width;
  const double pixels_per_metre = width / stage::SandtrayGeometry::screen_width;
  const auto signature = screen_signature(*snapshot.tray, pixels_per_metre);
  screen_checked_t_ = snapshot.t;
  if (screen_signature_ == signature) return;
  screen_signature_ = signature;
  cv::Mat picture = snapshot.tray->render_screen(width);
  if (screen_overlay_) screen_overlay_(picture);
  stage_.set_screen_image(picture);
  ++screen_updates_;
}

void StageMirror::set_screen_overlay(std::function<void(cv::Mat& bgr)> overlay) {
  screen_overlay_ = std::move(overlay);
  screen_signature_.reset();
  screen_checked_t_ = -1e9;
}

void StageMirror::pose_robot(const RobotSnapshot& robot) {
  if (joint_slots_.size() != robot.joint_names.size()) {
    joint_slots_.clear();
    for (const auto& name : robot.joint_names) joint_slots_.push_back(stage::nao_joint_index(name));
  }
  for (std::size_t i = 0; i < robot.positions.size() && i < joint_slots_.size(); ++i) {
    if (joint_slots_[i] >= 0) joints_[static_cast<std::size_t>(joint_slots_[i])] = robot.positions[i];
  }
  nao_->set_joint_targets(joints_);
}

void StageMirror::pose_child(const ChildSnapshot& child) {
  auto it = std::find_if(avatars_.begin(), avatars_.end(), [&](const auto& a) { return a.first == child.seat; });
  if (it == avatars_.end()) {
    const auto role = role_of(child.seat);
    if (!stage_.model().avatar(role).present) return;  // e.g. a yellow child in a child-robot scene
    avatars_.emplace_back(child.seat, stage::AvatarController(stage_, role));
    it = std::prev(avatars_.end());
  }
  auto& avatar = it->second;
  avatar.look_at(child.gaze_point);
  if (!child.touches.empty()) {
    const Vec2& p = child.touches.front().second;
    avatar.touch(Eigen::Vector2d(p.x(), p.y()), stage::Hand::right);
  } else {
    avatar.lower_hand(stage::Hand::right);
  }
}

// ---- CameraRig -----------------------------------------------------------------------------------------------

CameraRig::CameraRig(const scenario::Scenario& scenario, stage::RendererOptions options, std::vector<FrameSink*> sinks)
    : cameras_(scenario.cameras), options_(options), sinks_(std::move(sinks)) {}

CameraRig::~CameraRig() = default;

void CameraRig::begin(const EpisodeInfo& /*info*/) {
  next_frame_.assign(cameras_.size(), 0);
  frames_.assign(cameras_.size(), 0);
  wall_render_s_.assign(cameras_.size(), 0.0);
}

void CameraRig::start(const EpisodeSnapshot& snapshot) {
  auto model = stage::StageModel::create(stage_config_for(snapshot));
  stage::RendererOptions options = options_;
  options.max_width = 1;
  options.max_height = 1;
  for (const auto& camera : cameras_) {
    const auto [color, depth] = image_sizes(*model, camera);  // throws InputError for a camera not in the scene
    options.max_width = std::max({options.max_width, color.width, depth.width});
    options.max_height = std::max({options.max_height, color.height, depth.height});
  }
  mirror_ = std::make_unique<StageMirror>(model);
  renderer_ = std::make_unique<stage::Renderer>(model, options);
  gl_renderer_ = renderer_->gl_renderer();
  for (auto* sink : sinks_) sink->set_gl_renderer(gl_renderer_);
}

void CameraRig::observe(const EpisodeSnapshot& snapshot) {
  if (cameras_.empty()) return;
  if (next_frame_.size() != cameras_.size()) begin({});
  // Frames k with k / rate ≤ t are due (a small tolerance absorbs the clock's rounding at exact multiples).
  std::vector<std::int64_t> due(cameras_.size(), 0);
  bool any = false;
  for (std::size_t i = 0; i < cameras_.size(); ++i) {
    const auto last_due = static_cast<std::int64_t>(std::floor(snapshot.t * cameras_[i].rate_hz + 1e-6));
    due[i] = std::max<std::int64_t>(0, last_due + 1 - next_frame_[i]);
    any = any || due[i] > 0;
  }
  if (!any) return;
  if (renderer_ == nullptr) start(snapshot);
  mirror_->pose(snapshot);
  for (std::size_t i = 0; i < cameras_.size(); ++i) {
    if (due[i] == 0) continue;
    const auto& camera = cameras_[i];
    stage::RenderRequest request;
    request.rgb = true;
    request.depth = camera.depth;
    request.width = camera.width;
    request.height = camera.height;
    const auto wall_start = std::chrono::steady_clock::now();
    stage::FramePack frame = renderer_->render(mirror_->stage(), camera.name, request);
    wall_render_s_[i] += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    for (std::int64_t k = next_frame_[i]; k < next_frame_[i] + due[i]; ++k) {
      frame.stamp = static_cast<double>(k) / camera.rate_hz;
      for (auto* sink : sinks_) sink->write(frame);
    }
    next_frame_[i] += due[i];
    frames_[i] += due[i];
  }
}

void CameraRig::end(EpisodeResult& result) {
  if (cameras_.empty()) return;
  if (!gl_renderer_.empty()) result.record["gl_renderer"] = gl_renderer_;
  auto& cameras = result.record["cameras"];
  for (std::size_t i = 0; i < cameras_.size(); ++i) {
    cameras["frames"][cameras_[i].name] = i < frames_.size() ? frames_[i] : 0;
    cameras["wall_render_s"][cameras_[i].name] = i < wall_render_s_.size() ? wall_render_s_[i] : 0.0;
  }
}

}  // namespace freeplay::runner
