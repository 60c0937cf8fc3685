#pragma once
// Where an OpenPose-style detector would put its keypoints on a child avatar: the 18 COCO body points, the 70 face
// points (68 iBUG landmarks + 2 pupils) and 21 points per hand, in the sandtray frame, from the avatar's posed bodies
// and a face landmark template on its head (ground truth for freeplay.poses.json and the PInSoRo table).

#include <array>

#include <Eigen/Core>

#include "freeplay/stage/stage.hpp"

namespace freeplay::stage {

/// COCO-18 body points in OpenPose order.
enum class CocoPoint {
  nose, neck, r_shoulder, r_elbow, r_wrist, l_shoulder, l_elbow, l_wrist, r_hip, r_knee, r_ankle, l_hip, l_knee,
  l_ankle, r_eye, l_eye, r_ear, l_ear
};
inline constexpr int kCocoPoints = 18;  ///< body points
inline constexpr int kFacePoints = 70;  ///< 68 iBUG landmarks + the two pupils (OpenPose's face model)
inline constexpr int kHandPoints = 21;  ///< wrist + 4 per finger (OpenPose's hand model)

/// Keypoints of one avatar in the sandtray frame (m).
struct AvatarKeypoints {
  std::array<Eigen::Vector3d, kCocoPoints> body;                 ///< COCO order
  std::array<Eigen::Vector3d, kFacePoints> face;                 ///< iBUG 68 order, then right and left pupil
  std::array<std::array<Eigen::Vector3d, kHandPoints>, 2> hands; ///< 0 = right, 1 = left; wrist first
};

/// The keypoints of the `role` child on `stage` as posed (after Stage::update_kinematics); InputError when the
/// scene has no such child.
AvatarKeypoints avatar_keypoints(const Stage& stage, ChildRole role);

/// The face landmark template: each point as (lateral u, vertical v) on the unit face disc seen from the front
/// (u > 0 towards the child's left, v > 0 up), placed on the head sphere by avatar_keypoints.
const std::array<Eigen::Vector2d, kFacePoints>& face_template();

}  // namespace freeplay::stage
