// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/base/pose.h"
#include "icgp/modality/measured_occlusion.h"
#include "icgp/render/scene_renderer.h"

namespace icgp {

/// An image point found on the body surface: which of the points handed to
/// SurfaceLifter::lift it was, and where it is on the body.
struct SurfacePoint {
  int index = 0;
  Eigen::Vector3f body_point;
  /// The surface normal there, from the render's depth; zero where the neighbouring render
  /// pixels are not all on the body (an edge of the silhouette).
  Eigen::Vector3f body_normal = Eigen::Vector3f::Zero();
};

/// Lifts image points onto the body surface (ALGORITHMS.md §7): back-projects the points
/// that fall on the body in a focused render of the scene at the body's pose to body-frame
/// points, and drops the ones a depth measurement shows to be occluded. The texture cue's
/// keyframes and the flow cue's tracked corners are made this way.
class SurfaceLifter {
 public:
  explicit SurfaceLifter(MeasuredOcclusion occlusion) : occlusion_(occlusion) {}

  /// `render` must show the body (id `body_id`) where the points were found, in the camera
  /// of intrinsics `k`; `depth` may be null (no occlusion test).
  std::vector<SurfacePoint> lift(const Intrinsics& k, const Pose& camera_T_body, const FocusedRender& render,
                                 std::uint8_t body_id, const std::vector<cv::Point2f>& points,
                                 const DepthImage* depth, const Pose& depth_T_camera) const;

 private:
  MeasuredOcclusion occlusion_;
};

}  // namespace icgp
