// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>

namespace icgp {

/// A point-to-plane pair of the depth cue (ALGORITHMS.md §5): a point of the body's surface
/// with its normal, both in the body frame, and the measured point it is fitted to.
struct DepthCorrespondence {
  Eigen::Vector3f body_point;
  Eigen::Vector3f body_normal;
  Eigen::Vector3f measured;  ///< in the depth camera frame
};

}  // namespace icgp
