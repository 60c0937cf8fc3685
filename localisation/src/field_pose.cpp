#include "freeplay/localisation/field_pose.hpp"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace freeplay::localisation {

std::optional<FieldPose> estimate_field_pose(const std::vector<MarkerDetection>& detections, const MarkerField& field,
                                             const Pinhole& camera) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  FieldPose out;
  for (const auto& d : detections) {
    const auto index = field.index_of(d.id);
    if (!index) continue;
    out.ids.push_back(d.id);
    const auto corners = field.corners(*index);
    for (std::size_t k = 0; k < 4; ++k) {
      object.emplace_back(corners[k].x(), corners[k].y(), corners[k].z());
      image.emplace_back(d.corners[k].x, d.corners[k].y);
    }
  }
  if (object.empty()) return std::nullopt;
  const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  cv::Vec3d rvec, tvec;
  // IPPE solves the planar case in closed form; Levenberg–Marquardt then polishes it on every corner.
  if (!cv::solvePnP(object, image, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE)) return std::nullopt;
  cv::solvePnPRefineLM(object, image, K, cv::noArray(), rvec, tvec);
  std::vector<cv::Point2d> reprojected;
  cv::projectPoints(object, rvec, tvec, K, cv::noArray(), reprojected);
  double sum = 0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const cv::Point2d e = reprojected[i] - image[i];
    sum += e.dot(e);
  }
  out.rms_reprojection_px = std::sqrt(sum / static_cast<double>(image.size()));
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d rotation;
  cv::cv2eigen(R, rotation);
  out.camera_T_sandtray.linear() = rotation;
  out.camera_T_sandtray.translation() = Eigen::Vector3d(tvec[0], tvec[1], tvec[2]);
  if (!out.camera_T_sandtray.matrix().allFinite()) return std::nullopt;
  return out;
}

}  // namespace freeplay::localisation
