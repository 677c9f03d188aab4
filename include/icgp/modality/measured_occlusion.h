// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/geometry/rounding.h"

namespace icgp {

/// The occlusion test of ALGORITHMS.md §7 on any depth image: `point` (camera frame) is
/// hidden when a depth within `radius` (metres) of its projection is closer than
/// Z − depth_offset − threshold. `depth_at(row, col)` is the depth of a pixel of the
/// rows × cols image of intrinsics `k` (0: none). Measured occlusions read a depth camera,
/// modeled ones a render of the other bodies.
template <typename DepthAt>
bool closer_depth_nearby(const Intrinsics& k, int rows, int cols, DepthAt&& depth_at, const Eigen::Vector3f& point,
                         float depth_offset, double radius, double threshold) {
  if (point.z() <= 0.f) return false;
  const Eigen::Vector2f centre = k.project<float>(point);
  const float radius_px = static_cast<float>(radius * k.fu) / point.z();
  // Samples one radius apart: an occluder wider than the radius that reaches into the
  // square covers one of them, and the test runs for every line and point of a frame. They
  // lie on the image lattice of multiples of `step`, so that the tests of neighbouring
  // points read the same pixels (few distinct pixels per frame, see DepthImage::source).
  const int step = std::max(1, static_cast<int>(std::ceil(radius_px)));
  const int row_min = std::max(0, lattice_ceil(centre.y() - radius_px, step));
  const int row_max = std::min(rows - 1, static_cast<int>(std::floor(centre.y() + radius_px)));
  const int col_min = std::max(0, lattice_ceil(centre.x() - radius_px, step));
  const int col_max = std::min(cols - 1, static_cast<int>(std::floor(centre.x() + radius_px)));
  const float limit = point.z() - depth_offset - static_cast<float>(threshold);
  for (int row = row_min; row <= row_max; row += step)
    for (int col = col_min; col <= col_max; col += step) {
      const float z = depth_at(row, col);
      if (z > 0.f && z < limit) return true;
    }
  return false;
}

/// The measured-occlusion test of ALGORITHMS.md §7: a model point is hidden when a depth
/// measurement within `radius` of its projection is closer than
/// Z − depth_offset − threshold. The depth offset (from the viewpoint model) accounts
/// for the object's own surface rising towards the camera around the point.
struct MeasuredOcclusion {
  double radius = 0.01;     ///< metres
  double threshold = 0.03;  ///< metres

  /// `point` is in the depth camera frame; `depth_offset` is the model's offset for `radius`.
  bool occluded(const DepthImage& depth, const Eigen::Vector3f& point, float depth_offset) const {
    return closer_depth_nearby(
        depth.intrinsics, depth.depth.rows, depth.depth.cols, [&](int row, int col) { return depth.at(row, col); },
        point, depth_offset, radius, threshold);
  }
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
