#include "freeplay/localisation/nao_view.hpp"

#include "freeplay/core/error.hpp"
#include "freeplay/stage/stage_state.hpp"

namespace freeplay::localisation {

Eigen::Isometry3d sandtray_T_odom(const stage::StageModel& model) {
  const auto& nao = model.nao();
  if (!nao.present) throw InputError("this stage has no NAO to localise", "scene", "child-robot");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = nao.sole_anchor;
  pose.linear() = Eigen::AngleAxisd(nao.facing_yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return pose;
}

Eigen::Isometry3d odom_T_shoulder(const stage::Stage& stage) {
  const int shoulder = stage.model().nao().rshoulder_body;
  Eigen::Isometry3d sandtray_T_shoulder = Eigen::Isometry3d::Identity();
  sandtray_T_shoulder.translation() = stage::body_pose(stage, shoulder).translation();
  sandtray_T_shoulder.linear() = stage::body_rotation(stage, shoulder);
  return sandtray_T_odom(stage.model()).inverse() * sandtray_T_shoulder;
}

NaoCameraView nao_camera_view(stage::Renderer& renderer, const stage::Stage& stage, std::string_view camera) {
  const Eigen::Isometry3d odom_T_sandtray = sandtray_T_odom(stage.model()).inverse();
  stage::FramePack frame = renderer.render(stage, camera);
  NaoCameraView view;
  view.image = std::move(frame.rgb);
  view.camera = {frame.K.fx, frame.K.fy, frame.K.cx, frame.K.cy};
  view.odom_T_camera = odom_T_sandtray * frame.sandtray_T_camera_optical;
  view.odom_T_shoulder = odom_T_shoulder(stage);
  view.odom_T_sandtray_truth = odom_T_sandtray;
  return view;
}

}  // namespace freeplay::localisation
