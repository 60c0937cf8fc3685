#include "freeplay/localisation/localiser.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <utility>

#include "freeplay/localisation/aruco.hpp"

namespace freeplay::localisation {

Localiser::Localiser(LocaliserSettings settings) : settings_(std::move(settings)) {}

void Localiser::on_signal(double t) {
  spdlog::info("localisation: looking for the fiducial markers on the sandtray for {} s max", settings_.search_s);
  search_started_ = t;
}

bool Localiser::on_frame(double t, const cv::Mat& image, const Pinhole& camera, const Eigen::Isometry3d& odom_T_camera) {
  tick(t);
  if (!looking()) return false;
  const auto fit = estimate_field_pose(detect_markers(image), settings_.field, camera);
  if (!fit) return false;
  odom_T_sandtray_ = odom_T_camera * fit->camera_T_sandtray;
  last_fit_ = fit;
  search_started_.reset();
  ++successes_;
  spdlog::info("localisation: found {} fiducial markers (rms {:.2f} px); broadcasting odom->sandtray", fit->ids.size(),
               fit->rms_reprojection_px);
  speech_.emplace_back(kFoundSpeech);
  return true;
}

void Localiser::tick(double t) {
  if (!search_started_ || t - *search_started_ < settings_.search_s - 1e-9) return;
  spdlog::error("localisation: no fiducial marker seen after {} s; is the sandtray in the robot camera's view?",
                settings_.search_s);
  search_started_.reset();
  ++failures_;
  speech_.emplace_back(kLostSpeech);
}

std::optional<ArmReachFrame> Localiser::arm_reach(const Eigen::Isometry3d& odom_T_shoulder) const {
  if (!odom_T_sandtray_ || !settings_.broadcast_arm_reach) return std::nullopt;
  const Eigen::Isometry3d sandtray_T_shoulder = odom_T_sandtray_->inverse() * odom_T_shoulder;
  const double height = sandtray_T_shoulder.translation().z();
  if (height > settings_.arm_reach_m) {
    if (!warned_too_high_) spdlog::warn("localisation: too high! distance from shoulder to sandtray > arm reach");
    warned_too_high_ = true;
    return std::nullopt;
  }
  ArmReachFrame out;
  out.translation = sandtray_T_shoulder.translation();
  out.translation.z() = std::sqrt(settings_.arm_reach_m * settings_.arm_reach_m - height * height);
  out.rotation = Eigen::Quaterniond(sandtray_T_shoulder.linear()).normalized();
  return out;
}

std::vector<std::string> Localiser::take_speech() { return std::exchange(speech_, {}); }

PoseError pose_error(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth) {
  PoseError e;
  e.translation_m = (estimate.translation() - truth.translation()).norm();
  e.rotation_deg = Eigen::AngleAxisd(estimate.linear().transpose() * truth.linear()).angle() * 180.0 / M_PI;
  return e;
}

}  // namespace freeplay::localisation
