// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/detection/training_views.h"

namespace icgp {

/// A textured body's appearance as ORB keypoints on its model (docs/detection.md): learnt
/// from renders of its mesh at known poses, each keypoint lifted onto the surface. In an
/// image, keypoints matched to them give 2D-3D correspondences, and PnP with RANSAC pose
/// hypotheses that hold wherever the texture shows, with or without depth and whatever
/// the shape's symmetry.
class KeypointModel {
 public:
  explicit KeypointModel(const std::vector<TrainingView>& views);

  /// Too few keypoints on the model to locate it (a mesh without enough texture).
  bool empty() const { return points_.size() < kMinModelPoints; }

  struct Located {
    Pose camera_T_body;
    int inliers = 0;  ///< correspondences within the reprojection threshold
    int matches = 0;  ///< correspondences tried
  };
  /// The poses the keypoints of `grey` (CV_8UC1, camera `K`) put the body at: one, or two
  /// when the correspondences that agree lie on a plane (which a turned plane mimics),
  /// the better first; none when fewer than kMinInliers agree.
  std::vector<Located> locate(const cv::Mat& grey, const Intrinsics& K) const;

  static constexpr std::size_t kMinModelPoints = 30;
  static constexpr int kMinInliers = 12;

 private:
  cv::Ptr<cv::ORB> image_features_;
  cv::Mat descriptors_;                  ///< one row per model point
  std::vector<Eigen::Vector3f> points_;  ///< body frame
  /// Model points in one small cell: one surface point seen from several views.
  std::vector<int> groups_;
};

}  // namespace icgp
