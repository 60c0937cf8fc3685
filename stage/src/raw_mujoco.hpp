#pragma once
// The raw MuJoCo model and state behind StageModel and Stage: for stage/'s own sources (and its tests and
// benchmarks) only. Stage/'s public headers name no MuJoCo type; the configure-time check in stage/CMakeLists.txt
// keeps MuJoCo's headers out of them and out of every other library.

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <filesystem>

#include "freeplay/stage/stage.hpp"
#include "freeplay/stage/stage_model.hpp"

namespace freeplay::stage {

/// The MuJoCo model a StageModel owns.
struct StageModel::Raw {
  mjModel* model = nullptr;   ///< owned
  Raw() = default;
  Raw(const Raw&) = delete;
  Raw& operator=(const Raw&) = delete;
  ~Raw() { if (model != nullptr) mj_deleteModel(model); }
};

/// The MuJoCo state a Stage owns.
struct Stage::Raw {
  mjData* data = nullptr;     ///< owned
  Raw() = default;
  Raw(const Raw&) = delete;
  Raw& operator=(const Raw&) = delete;
  ~Raw() { if (data != nullptr) mj_deleteData(data); }
};

/// The one door from stage/'s sources to the raw model and state (a friend of StageModel and Stage).
struct RawMujoco {
  /// The MuJoCo model of `model`.
  static const mjModel* model(const StageModel& model) { return model.raw_->model; }
  /// The MuJoCo state of `stage`.
  static mjData* data(const Stage& stage) { return stage.raw_->data; }
};

/// The MuJoCo model of `model` (read-only).
inline const mjModel* raw_model(const StageModel& model) { return RawMujoco::model(model); }
/// The MuJoCo state of `stage` (read-only).
inline const mjData* raw_data(const Stage& stage) { return RawMujoco::data(stage); }
/// The MuJoCo state of `stage` (for controllers).
inline mjData* raw_data(Stage& stage) { return RawMujoco::data(stage); }

/// Loads a standalone MJCF file; throws std::runtime_error with the path and MuJoCo's message.
mjModel* load_mjcf_file(const std::filesystem::path& path);

/// The sandtray pose of a MuJoCo camera's optical frame (x right, y down, z forward) from the state `d`.
Eigen::Isometry3d camera_optical_pose(const mjModel* m, const mjData* d, int camera_id);

}  // namespace freeplay::stage
