// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>

#include "icgp/eval/frame.h"

namespace icgp {

/// The measured-occlusion test of ALGORITHMS.md §7: a model point is hidden when a depth
/// measurement within `radius` of its projection is closer than
/// Z − depth_offset − threshold. The depth offset (from the viewpoint model) accounts
/// for the object's own surface rising towards the camera around the point.
struct MeasuredOcclusion {
  double radius = 0.01;     ///< metres
  double threshold = 0.03;  ///< metres

  /// `point` is in the depth camera frame; `depth_offset` is the model's offset for `radius`.
  bool occluded(const DepthImage& depth, const Eigen::Vector3f& point, float depth_offset) const;
};

}  // namespace icgp
