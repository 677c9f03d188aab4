// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/detection/training_views.h"

namespace icgp {

/// ViSP's own detection path, the baseline icgp's detector is compared with: vpKeyPoint
/// with ORB keypoints and descriptors, trained the way ViSP's tutorial "object detection
/// and localization with keypoints" does (keypoints detected on images of the object at
/// known poses, lifted onto the model, `buildReference`, appended over the images), then
/// `matchPoint(I, cam, cMo)`: ratio test 0.8, RANSAC on the virtual visual servoing pose,
/// 200 iterations, consensus 20 %, threshold 0.005 (the tutorial's settings). It learns
/// from the same TrainingViews as icgp's KeypointModel; where the tutorial lifts keypoints
/// with the .cao faces, the render's depth lifts them here (the same points for a mesh).
class KeypointBaseline {
 public:
  explicit KeypointBaseline(const std::vector<TrainingView>& views);
  ~KeypointBaseline();

  /// The pose vpKeyPoint finds in `grey` (CV_8UC1, camera `K`), or nothing.
  std::optional<Pose> locate(const cv::Mat& grey, const Intrinsics& K);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace icgp
