#pragma once
// The Nao's link frames for /tf, by forward kinematics of the child-robot stage: what naoqi_driver's
// robot_state_publisher broadcasts (the nao_description URDF tree) from the recorded joint angles.

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "freeplay/stage/stage.hpp"

namespace freeplay::recording {

/// One Nao link frame as /tf carries it.
struct LinkTransform {
  std::string parent;                                                 ///< parent frame
  std::string child;                                                  ///< the link
  Eigen::Isometry3d parent_T_child = Eigen::Isometry3d::Identity();   ///< pose of the link in its parent
};

/// Forward kinematics of the Nao links on a kinematic child-robot stage owned by this object.
class NaoLinkFrames {
 public:
  /// A child-robot stage with the scenario's arm reach (it places the Nao like the episode's robot body).
  explicit NaoLinkFrames(double arm_reach_m = 0.5);
  ~NaoLinkFrames();
  NaoLinkFrames(const NaoLinkFrames&) = delete;
  NaoLinkFrames& operator=(const NaoLinkFrames&) = delete;

  /// The link frames for the joint angles `positions` of the joints `names` (sensor_msgs/JointState order; names
  /// that are not Nao joints: InputError): `base_link` in `sandtray`, `torso` in `base_link` (identity, as the
  /// URDF's fixed joint), and every other link of the URDF tree in its parent link.
  const std::vector<LinkTransform>& compute(const std::vector<std::string>& names, const std::vector<double>& positions);
  /// The stage after the last compute (body poses in the sandtray frame).
  const stage::Stage& stage() const { return *stage_; }

 private:
  std::unique_ptr<stage::Stage> stage_;
  std::vector<int> link_bodies_;  // MuJoCo bodies of the Nao below the torso, parents first
  std::vector<LinkTransform> out_;
};

}  // namespace freeplay::recording
