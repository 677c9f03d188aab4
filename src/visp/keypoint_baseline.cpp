// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/visp/keypoint_baseline.h"

#include <visp3/core/vpException.h>
#include <visp3/vision/vpKeyPoint.h>

#include "icgp/visp/conversions.h"

namespace icgp {

struct KeypointBaseline::Impl {
  vpKeyPoint keypoints{"ORB", "ORB", "BruteForce-Hamming", vpKeyPoint::ratioDistanceThreshold};
};

KeypointBaseline::KeypointBaseline(const std::vector<TrainingView>& views) : impl_(std::make_unique<Impl>()) {
  vpKeyPoint& k = impl_->keypoints;
  k.setMatchingRatioThreshold(0.8);
  k.setUseRansacVVS(true);
  k.setUseRansacConsensusPercentage(true);
  k.setRansacConsensusPercentage(20.0);
  k.setRansacIteration(200);
  k.setRansacThreshold(0.005);
  bool append = false;
  for (const TrainingView& view : views) {
    vpImage<unsigned char> I;
    to_vp_image(view.grey, I);
    std::vector<cv::KeyPoint> detected, on_body;
    double elapsed = 0.0;
    k.detect(view.grey, detected, elapsed, view.mask);
    std::vector<cv::Point3f> points;
    for (const cv::KeyPoint& p : detected) {
      Eigen::Vector3f X;
      if (!view.lift(p.pt.x, p.pt.y, X)) continue;
      on_body.push_back(p);
      points.emplace_back(X.x(), X.y(), X.z());
    }
    if (on_body.empty()) continue;
    k.buildReference(I, on_body, points, append);
    append = true;
  }
}

KeypointBaseline::~KeypointBaseline() = default;

std::optional<Pose> KeypointBaseline::locate(const cv::Mat& grey, const Intrinsics& K) {
  vpImage<unsigned char> I;
  to_vp_image(grey, I);
  vpHomogeneousMatrix cMo;
  double error = 0.0, elapsed = 0.0;
  try {
    if (!impl_->keypoints.matchPoint(I, to_camera_parameters(K), cMo, error, elapsed)) return std::nullopt;
  } catch (const vpException&) {
    return std::nullopt;  // too few matches for a pose: not found, as matchPoint's false
  }
  return to_pose(cMo);
}

}  // namespace icgp
