// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <vector>

#include "icgp/base/frame.h"

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

/// Which points of one model view are occluded, measured once per frame: the pose moves by
/// far less than the occlusion radius between correspondence iterations, so repeating the
/// test at every iteration would only cost time.
class ViewOcclusions {
 public:
  /// Measures the first n_points points of `view` with is_occluded(i) at a frame's first
  /// correspondence iteration, or when the view changed since the last measurement.
  template <typename IsOccluded>
  void update(int corr_iter, int view, int n_points, IsOccluded&& is_occluded) {
    if (corr_iter != 0 && view == view_ && n_points == static_cast<int>(flags_.size())) return;
    flags_.resize(n_points);
    for (int i = 0; i < n_points; ++i) flags_[i] = is_occluded(i);
    view_ = view;
  }
  /// True when point i of `view` has been measured.
  bool measured(int view, int i) const { return view == view_ && i < static_cast<int>(flags_.size()); }
  bool occluded(int i) const { return flags_[i]; }
  void reset() { view_ = -1; }

 private:
  std::vector<bool> flags_;
  int view_ = -1;
};

}  // namespace icgp
