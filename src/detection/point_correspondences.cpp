// SPDX-License-Identifier: GPL-2.0-or-later
#include "point_correspondences.h"

#include <opencv2/calib3d.hpp>

namespace icgp {

void PointCorrespondences::add(const Eigen::Vector3f& body_point, const cv::Point2f& image_point) {
  model.emplace_back(body_point.x(), body_point.y(), body_point.z());
  image.push_back(image_point);
}

PointCorrespondences PointCorrespondences::subset(const std::vector<int>& indices) const {
  PointCorrespondences out;
  for (const int i : indices) {
    out.model.push_back(model[i]);
    out.image.push_back(image[i]);
  }
  return out;
}

cv::Matx33d camera_matrix(const Intrinsics& K) { return {K.fu, 0.0, K.pu, 0.0, K.fv, K.pv, 0.0, 0.0, 1.0}; }

std::optional<Pose> refined_pose(const PointCorrespondences& inliers, const Intrinsics& K, cv::Mat rvec, cv::Mat tvec) {
  cv::solvePnPRefineLM(inliers.model, inliers.image, camera_matrix(K), cv::noArray(), rvec, tvec);
  const Pose camera_T_body = Pose::from_rotation_vector(Eigen::Vector3d(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2)),
                                                        Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
  if (!(camera_T_body.translation().z() > 0.0)) return std::nullopt;
  return camera_T_body;
}

}  // namespace icgp
