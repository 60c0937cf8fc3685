#pragma once
// The mutable 3-D stage of one episode: MuJoCo state, the live screen image, kinematic or dynamic stepping.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string_view>
#include <vector>

#include "freeplay/stage/stage_mode.hpp"
#include "freeplay/stage/stage_model.hpp"

namespace freeplay::stage {

/// Per-episode state of the stage; owned by one thread.
class Stage {
 public:
  /// A stage at rest: children seated looking at the screen centre, the NAO (if any) in StandInit.
  explicit Stage(std::shared_ptr<const StageModel> model, StageMode mode = StageMode::kinematic);
  ~Stage();
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;

  /// The immutable model.
  const StageModel& model() const { return *model_; }
  /// The shared model pointer (for renderers and controllers).
  const std::shared_ptr<const StageModel>& shared_model() const { return model_; }
  /// Kinematic or dynamic.
  StageMode mode() const { return mode_; }
  /// Simulated time (s).
  double time() const;

  /// Replaces the sandtray screen picture (BGR or grey, any size; resampled to the texture size).
  void set_screen_image(const cv::Mat& bgr);
  /// The screen texture as RGB pixels; row 0 is the screen's top edge (sandtray y = 0).
  const cv::Mat& screen_texture() const { return screen_rgb_; }
  /// Changes whenever the screen picture changes; unique across all stages of the process.
  std::uint64_t screen_version() const { return screen_version_; }

  /// Recomputes every pose (bodies, sites, cameras) from the joint angles: the kinematic update.
  void update_kinematics();
  /// Dynamic mode only: advances the physics `steps` timesteps (2 ms each); avatars keep their kinematic pose.
  void step(int steps = 1);

  /// World (sandtray) position of a MuJoCo site after the last update.
  Eigen::Vector3d site_position(int site_id) const;
  /// Sandtray pose of a camera's optical frame (x right, y down, z forward) after the last update.
  Eigen::Isometry3d camera_pose(std::string_view camera_name) const;

  /// qpos addresses of the avatar joints (held fixed by dynamics).
  const std::vector<int>& avatar_qpos() const { return avatar_qpos_; }

 private:
  friend struct RawMujoco;   // stage/src/raw_mujoco.hpp: the raw state, for stage/'s sources only
  struct Raw;                // the MuJoCo state (stage/src/raw_mujoco.hpp)

  std::shared_ptr<const StageModel> model_;
  StageMode mode_;
  std::unique_ptr<Raw> raw_;
  cv::Mat screen_rgb_;
  std::uint64_t screen_version_ = 0;
  std::vector<int> avatar_qpos_;
  std::vector<int> avatar_dofs_;
  std::vector<double> held_qpos_;
};

}  // namespace freeplay::stage

namespace freeplay::stage {

/// A procedural stand-in for the sandtray game picture (grass, a lake, a few coloured blobs, a red marker in
/// the top-left corner), BGR, `width`×`height`: a fixed test picture for rendering tests and benchmarks.
cv::Mat demo_screen_image(int width = 1920, int height = 1080);

}  // namespace freeplay::stage
