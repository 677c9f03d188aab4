// SPDX-License-Identifier: GPL-2.0-or-later
// 2D-3D correspondences and the PnP steps the keypoint model and the texture alignment
// share (private to the detection module).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"

namespace icgp {

/// Model points (body frame) and the image points they are seen at, pair by pair.
struct PointCorrespondences {
  std::vector<cv::Point3f> model;
  std::vector<cv::Point2f> image;

  std::size_t size() const { return model.size(); }
  void add(const Eigen::Vector3f& body_point, const cv::Point2f& image_point);
  /// The pairs at `indices` (e.g. RANSAC's inliers).
  PointCorrespondences subset(const std::vector<int>& indices) const;
};

/// OpenCV's camera matrix of `K`.
cv::Matx33d camera_matrix(const Intrinsics& K);

/// camera_T_body refined by Levenberg–Marquardt on the reprojection error of `inliers`,
/// from the rotation vector and translation (rvec, tvec) of a PnP solution; nothing when
/// the body ends up behind the camera.
std::optional<Pose> refined_pose(const PointCorrespondences& inliers, const Intrinsics& K, cv::Mat rvec, cv::Mat tvec);

}  // namespace icgp
