#pragma once
// The pose of the marker field (= the `sandtray` frame) in a camera's optical frame from detected markers.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "freeplay/localisation/aruco.hpp"
#include "freeplay/localisation/marker_field.hpp"

namespace freeplay::localisation {

/// A calibrated pinhole camera without distortion (the simulated cameras have none), pixel centres at integers.
struct Pinhole {
  double fx = 0;  ///< focal length along x (px)
  double fy = 0;  ///< focal length along y (px)
  double cx = 0;  ///< principal point x (px)
  double cy = 0;  ///< principal point y (px)
};

/// Where the field is, seen from the camera.
struct FieldPose {
  Eigen::Isometry3d camera_T_sandtray = Eigen::Isometry3d::Identity();  ///< sandtray pose in the optical frame
  std::vector<int> ids;                                                  ///< field markers used
  double rms_reprojection_px = 0;                                        ///< fit residual
};

/// Fits the field's pose to every detection that belongs to `field` (all their corners at once, as a board);
/// nothing when no field marker was detected or the fit fails.
std::optional<FieldPose> estimate_field_pose(const std::vector<MarkerDetection>& detections, const MarkerField& field,
                                             const Pinhole& camera);

}  // namespace freeplay::localisation
