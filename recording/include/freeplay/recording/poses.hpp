#pragma once
// Ground-truth keypoints as PInSoRo's `extract_poses` (OpenPose) writes them: `freeplay.poses.json`, per camera
// topic and 30 Hz frame, the children's 18 COCO body points, 70 face points and 21 points per hand, projected
// exactly from the posed avatars (free-play-sandbox.md §4.4). No rendering: the stage's kinematics only.

#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/stage/avatar_keypoints.hpp"

namespace freeplay::recording {

/// One keypoint in an image: pixels and confidence (OpenPose's [x, y, c]; 0, 0, 0 when not in the image).
struct ImagePoint {
  double x = 0.0;  ///< column (px)
  double y = 0.0;  ///< row (px)
  double c = 0.0;  ///< 1 in front of the camera and inside the image, else 0
};

/// The avatar keypoints of one child projected into one camera.
struct ProjectedKeypoints {
  std::array<ImagePoint, stage::kCocoPoints> body;                  ///< COCO order
  std::array<ImagePoint, stage::kFacePoints> face;                  ///< iBUG 68 + pupils
  std::array<std::array<ImagePoint, stage::kHandPoints>, 2> hands;  ///< right, left
};

/// Projects sandtray point `p` with a camera of intrinsics `K` at `sandtray_T_optical` (x right, y down, z forward).
ImagePoint project(const Eigen::Vector3d& p, const stage::CameraIntrinsics& K, const Eigen::Isometry3d& sandtray_T_optical);
/// Projects every keypoint of `k` into the camera.
ProjectedKeypoints project(const stage::AvatarKeypoints& k, const stage::CameraIntrinsics& K,
                           const Eigen::Isometry3d& sandtray_T_optical);

/// Poses the stage from each free-play snapshot and writes `freeplay.poses.json` for the colour topics of
/// camera_purple, camera_yellow and env_camera (person "1" = purple child, "2" = yellow child); also hands each
/// child's keypoints in its own camera to the PInSoRo table.
class PoseRecorder {
 public:
  /// Writes into `session_dir` (three part files while recording, joined by `finish`).
  explicit PoseRecorder(std::filesystem::path session_dir);
  ~PoseRecorder();
  PoseRecorder(const PoseRecorder&) = delete;
  PoseRecorder& operator=(const PoseRecorder&) = delete;

  /// Poses the stage at a free-play tick and writes its three 30 Hz frames; returns each child's keypoints in its
  /// own front camera (purple, yellow; empty when that child is absent), normalised to [0, 1] like the table.
  std::array<std::optional<ProjectedKeypoints>, 2> observe(const runner::EpisodeSnapshot& snapshot);
  /// Joins the parts into `freeplay.poses.json` and returns its path (nothing written when no frame was).
  std::optional<std::filesystem::path> finish();
  /// Removes the part files (an interrupted recording).
  void discard();

 private:
  struct Camera {
    std::string name, topic;
    std::filesystem::path part;
    std::ofstream out;
    bool first = true;
  };
  std::filesystem::path dir_;
  std::unique_ptr<runner::StageMirror> mirror_;
  std::vector<Camera> cameras_;
};

}  // namespace freeplay::recording
