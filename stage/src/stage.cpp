#include "freeplay/stage/stage.hpp"

#include <atomic>
#include <stdexcept>
#include <opencv2/imgproc.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/stage/avatar_controller.hpp"
#include "freeplay/stage/nao_controller.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {
namespace {

// Hands out screen versions that differ between stages, so a renderer never mistakes one stage's picture for
// another's. It carries no simulation state.
std::uint64_t next_screen_version() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace

Stage::Stage(std::shared_ptr<const StageModel> model, StageMode mode)
    : model_(std::move(model)), mode_(mode), raw_(std::make_unique<Raw>()) {
  const mjModel* m = raw_model(*model_);
  raw_->data = mj_makeData(m);
  const int tex = model_->screen_texture();
  screen_rgb_ = cv::Mat(m->tex_height[tex], m->tex_width[tex], CV_8UC3, m->tex_rgb + m->tex_adr[tex]).clone();
  screen_version_ = next_screen_version();
  for (ChildRole role : {ChildRole::purple, ChildRole::yellow}) {
    const AvatarIndex& a = model_->avatar(role);
    if (!a.present) continue;
    for (int dof : a.dofs) {
      avatar_dofs_.push_back(dof);
      avatar_qpos_.push_back(m->jnt_qposadr[m->dof_jntid[dof]]);
    }
    AvatarController(*this, role).rest();
  }
  if (model_->nao().present) NaoController(*this).go_to_posture(NaoPosture::StandInit);
  update_kinematics();
}

Stage::~Stage() = default;

double Stage::time() const { return raw_->data->time; }

void Stage::set_screen_image(const cv::Mat& bgr) {
  if (bgr.empty() || bgr.depth() != CV_8U || (bgr.channels() != 3 && bgr.channels() != 1)) {
    throw InputError("screen image must be a non-empty 8-bit BGR or grey image", "screen image",
                     "CV_8UC3 (BGR) or CV_8UC1");
  }
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, bgr.channels() == 3 ? cv::COLOR_BGR2RGB : cv::COLOR_GRAY2RGB);
  cv::resize(rgb, screen_rgb_, screen_rgb_.size(), 0, 0, cv::INTER_AREA);
  screen_version_ = next_screen_version();
}

void Stage::update_kinematics() {
  mj_kinematics(raw_model(*model_), raw_->data);
  mj_camlight(raw_model(*model_), raw_->data);
}

void Stage::step(int steps) {
  if (mode_ != StageMode::dynamic) throw std::logic_error("Stage::step needs a stage made in dynamic mode");
  if (steps < 0) throw InputError("step count must not be negative", "steps", ">= 0");
  const mjModel* m = raw_model(*model_);
  held_qpos_.resize(avatar_qpos_.size());
  for (size_t i = 0; i < avatar_qpos_.size(); ++i) held_qpos_[i] = raw_->data->qpos[avatar_qpos_[i]];
  for (int s = 0; s < steps; ++s) {
    mj_step(m, raw_->data);
    for (size_t i = 0; i < avatar_qpos_.size(); ++i) {
      raw_->data->qpos[avatar_qpos_[i]] = held_qpos_[i];
      raw_->data->qvel[avatar_dofs_[i]] = 0.0;
    }
  }
  update_kinematics();  // mj_step leaves poses one step behind the integrated joint angles
}

Eigen::Vector3d Stage::site_position(int site_id) const {
  return Eigen::Map<const Eigen::Vector3d>(raw_->data->site_xpos + 3 * site_id);
}

Eigen::Isometry3d Stage::camera_pose(std::string_view camera_name) const {
  return camera_optical_pose(raw_model(*model_), raw_->data, model_->camera(camera_name).camera_id);
}

}  // namespace freeplay::stage

namespace freeplay::stage {

cv::Mat demo_screen_image(int width, int height) {
  if (width < 16 || height < 16) throw InputError("demo screen image too small", "width/height", ">= 16 px");
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(68, 190, 115));  // light green grass (BGR)
  const double s = width / 1920.0;
  auto pt = [s](double x, double y) { return cv::Point(static_cast<int>(x * s), static_cast<int>(y * s)); };
  cv::ellipse(image, pt(450, 760), cv::Size(static_cast<int>(380 * s), static_cast<int>(220 * s)), 0, 0, 360,
              cv::Scalar(164, 101, 52), cv::FILLED);                                      // lake (blue)
  cv::rectangle(image, pt(1150, 80), pt(1650, 380), cv::Scalar(79, 233, 252), cv::FILLED);  // savanna (yellow)
  cv::circle(image, pt(900, 500), static_cast<int>(60 * s), cv::Scalar(33, 68, 120), cv::FILLED);  // item
  cv::circle(image, pt(1300, 750), static_cast<int>(60 * s), cv::Scalar(168, 127, 173), cv::FILLED);
  cv::rectangle(image, pt(1690, 0), pt(1920, 1080), cv::Scalar(52, 54, 46), cv::FILLED);  // stash strip
  cv::rectangle(image, pt(0, 0), pt(120, 120), cv::Scalar(0, 0, 230), cv::FILLED);  // top-left marker (red)
  return image;
}

}  // namespace freeplay::stage
