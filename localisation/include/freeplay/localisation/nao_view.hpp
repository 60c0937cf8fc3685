#pragma once
// The simulated NAO's side of localisation: its head camera's image of a stage and what its own kinematics tell
// it (the naoqi_driver TF tree: odom → camera, odom → RShoulder), plus the simulator's ground truth to score it.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string_view>

#include "freeplay/localisation/field_pose.hpp"
#include "freeplay/stage/renderer.hpp"
#include "freeplay/stage/stage.hpp"

namespace freeplay::localisation {

/// The NAO's top camera, as naoqi_driver's `camera/front` (the `image` of the real localisation node).
inline constexpr std::string_view kNaoLocalisationCamera = "CameraTop";

/// One frame of the NAO's camera with the robot's own knowledge of where the camera and the shoulder are.
struct NaoCameraView {
  cv::Mat image;                                                      ///< CV_8UC3 (R, G, B)
  Pinhole camera;                                                     ///< its calibration (no distortion)
  Eigen::Isometry3d odom_T_camera = Eigen::Isometry3d::Identity();    ///< optical frame in `odom`
  Eigen::Isometry3d odom_T_shoulder = Eigen::Isometry3d::Identity();  ///< RShoulder in `odom`
  Eigen::Isometry3d odom_T_sandtray_truth = Eigen::Isometry3d::Identity();  ///< ground truth (scoring only)
};

/// Where the NAO's `odom` frame lies in `sandtray`: on the floor under its soles' midpoint, x along its heading
/// (the simulated NAO never walks, so odom stays where it stands). Throws InputError for a scene without a NAO.
Eigen::Isometry3d sandtray_T_odom(const stage::StageModel& model);

/// Where the NAO's RShoulder (the real node's `arm_reach_origin_frame`) is in `odom` for the stage's current pose.
Eigen::Isometry3d odom_T_shoulder(const stage::Stage& stage);

/// Renders `camera` of the (kinematically up-to-date) `stage` and fills in the robot's kinematic frames.
NaoCameraView nao_camera_view(stage::Renderer& renderer, const stage::Stage& stage,
                              std::string_view camera = kNaoLocalisationCamera);

}  // namespace freeplay::localisation
