// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "icgp/base/body.h"
#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/render/scene_renderer.h"

namespace icgp {

/// Aligns a textured body's render with the image, for a pose that is already close
/// (docs/detection.md): corners of the render at the pose are followed into the image by
/// pyramidal Lucas-Kanade flow and, lifted onto the model by the render's depth, give
/// sub-pixel 2D-3D correspondences for a robust PnP; twice, each from the pose before.
/// Without depth this is what pins a detected pose to millimetres: the contour alone
/// leaves a monocular pose several millimetres off along the line of sight.
class TextureAlignment {
 public:
  /// `body` is rendered by `renderer`.
  TextureAlignment(SceneRenderer& renderer, const Body& body);

  /// The aligned reference_T_body of the body in `grey` (CV_8UC1, camera `K`, whose pose in
  /// the frame's reference is `camera_T_reference`), starting from `reference_T_body`; or
  /// nothing when too few correspondences agree. `occluders` are rendered with the body,
  /// so that what they hide is not followed.
  std::optional<Pose> align(const cv::Mat& grey, const Intrinsics& K, const Pose& camera_T_reference,
                            const Pose& reference_T_body, const std::vector<Body*>& occluders = {});

 private:
  /// One round: the pose the render's corners, followed into the image, put the body at.
  std::optional<Pose> round(const cv::Mat& grey, const Intrinsics& K, const Pose& camera_T_reference,
                            const Pose& reference_T_body, const std::vector<Body*>& occluders);

  SceneRenderer& renderer_;
  Body body_;
  Sphere sphere_;
};

}  // namespace icgp
