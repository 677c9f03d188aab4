// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/keypoint_model.h"

#include <array>
#include <limits>
#include <map>

#include <Eigen/Core>
#include <Eigen/SVD>
#include <opencv2/calib3d.hpp>

#include "icgp/features/hamming_matching.h"
#include "point_correspondences.h"

namespace icgp {
namespace {

/// ORB on every training render and on the image: eight levels 1.2 apart match a body
/// from 3.6 times nearer to 3.6 times farther than it was rendered. In the image, a body
/// 140 pixels across in front of a high-contrast clutter got too few of 1500 features at
/// FAST's default threshold (20) to be located; 3000 at threshold 10 located it (and the
/// textured box at 0.9 m in grey: 3 -> 8 of 12 frames), for about 30 ms of matching.
constexpr int kViewFeatures = 200;
constexpr int kImageFeatures = 3000;
constexpr int kImageFastThreshold = 10;
constexpr float kScaleFactor = 1.2f;
constexpr int kLevels = 8;
constexpr int kPatchSize = 31;  ///< ORB's default, and its edge threshold
/// Lowe's ratio test, against the nearest model point that is not the same surface point
/// seen from another view: points in one cell of a grid of kCellRadii of the model's
/// half-extent are taken for one.
constexpr double kRatio = 0.8;
constexpr double kCellRadii = 0.05;
/// RANSAC over the correspondences: pixels of reprojection error an inlier may have.
constexpr float kInlierPx = 6.0f;
constexpr int kRansacIterations = 500;
constexpr double kRansacConfidence = 0.999;
/// Inliers whose thinnest extent is below this share of their widest are taken as planar.
constexpr double kPlanarRatio = 0.05;

/// Whether the points lie on a plane: their thinnest extent a small part of their widest.
bool planar(const std::vector<cv::Point3f>& points) {
  Eigen::MatrixXd centred(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) centred.row(i) << points[i].x, points[i].y, points[i].z;
  centred.rowwise() -= centred.colwise().mean();
  const Eigen::Vector3d extent = Eigen::JacobiSVD<Eigen::MatrixXd>(centred).singularValues();
  return extent(2) < kPlanarRatio * extent(0);
}

}  // namespace

KeypointModel::KeypointModel(const std::vector<TrainingView>& views)
    : image_features_(cv::ORB::create(kImageFeatures, kScaleFactor, kLevels, kPatchSize, 0, 2, cv::ORB::HARRIS_SCORE,
                                      kPatchSize, kImageFastThreshold)) {
  const cv::Ptr<cv::ORB> view_features = cv::ORB::create(kViewFeatures, kScaleFactor, kLevels);
  std::vector<cv::Mat> rows;
  Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::max()), high = -low;
  for (const TrainingView& view : views) {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    view_features->detectAndCompute(view.grey, view.mask, keypoints, descriptors);
    for (std::size_t k = 0; k < keypoints.size(); ++k) {
      Eigen::Vector3f X;
      if (!view.lift(keypoints[k].pt.x, keypoints[k].pt.y, X)) continue;
      points_.push_back(X);
      rows.push_back(descriptors.row(static_cast<int>(k)));
      low = low.cwiseMin(X);
      high = high.cwiseMax(X);
    }
  }
  if (rows.empty()) return;
  cv::vconcat(rows, descriptors_);
  const float cell = static_cast<float>(kCellRadii * 0.5 * (high - low).norm());
  std::map<std::array<int, 3>, int> cells;
  for (const Eigen::Vector3f& X : points_) {
    const Eigen::Vector3f c = ((X - low) / cell).array().floor();
    const std::array<int, 3> key{static_cast<int>(c.x()), static_cast<int>(c.y()), static_cast<int>(c.z())};
    groups_.push_back(cells.emplace(key, static_cast<int>(cells.size())).first->second);
  }
}

std::vector<KeypointModel::Located> KeypointModel::locate(const cv::Mat& grey, const Intrinsics& K) const {
  if (empty()) return {};
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  image_features_->detectAndCompute(grey, cv::noArray(), keypoints, descriptors);
  if (keypoints.size() < static_cast<std::size_t>(kMinInliers)) return {};
  std::vector<TwoNearest> nearest;
  two_nearest_hamming(descriptors, descriptors_, nearest, &groups_);
  PointCorrespondences matched;
  for (std::size_t q = 0; q < nearest.size(); ++q) {
    const TwoNearest& n = nearest[q];
    if (n.train_index < 0 || n.best >= kRatio * n.second) continue;
    matched.add(points_[n.train_index], keypoints[q].pt);
  }
  if (matched.size() < static_cast<std::size_t>(kMinInliers)) return {};
  cv::Vec3d rvec, tvec;
  std::vector<int> inlier_indices;
  if (!cv::solvePnPRansac(matched.model, matched.image, camera_matrix(K), cv::noArray(), rvec, tvec, false,
                          kRansacIterations, kInlierPx, kRansacConfidence, inlier_indices, cv::SOLVEPNP_EPNP) ||
      inlier_indices.size() < static_cast<std::size_t>(kMinInliers))
    return {};
  const PointCorrespondences inliers = matched.subset(inlier_indices);
  // Keypoints of one face of a box lie on a plane, whose view a turned plane can mimic to
  // within the inlier threshold: then both of IPPE's poses are hypotheses, better first.
  std::vector<cv::Mat> rvecs{cv::Mat(rvec)}, tvecs{cv::Mat(tvec)};
  if (planar(inliers.model))
    cv::solvePnPGeneric(inliers.model, inliers.image, camera_matrix(K), cv::noArray(), rvecs, tvecs, false,
                        cv::SOLVEPNP_IPPE);
  std::vector<Located> located;
  for (std::size_t k = 0; k < rvecs.size(); ++k)
    // Refined on the inliers alone, by the reprojection error RANSAC judged them with.
    if (const std::optional<Pose> pose = refined_pose(inliers, K, rvecs[k], tvecs[k]))
      located.push_back({*pose, static_cast<int>(inliers.size()), static_cast<int>(matched.size())});
  return located;
}

}  // namespace icgp
