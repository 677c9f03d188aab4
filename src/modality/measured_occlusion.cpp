// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/measured_occlusion.h"

#include <algorithm>
#include <cmath>

#include "icgp/geometry/rounding.h"

namespace icgp {

bool MeasuredOcclusion::occluded(const DepthImage& depth, const Eigen::Vector3f& point, float depth_offset) const {
  if (point.z() <= 0.f) return false;
  const Intrinsics& k = depth.intrinsics;
  const Eigen::Vector2f centre = k.project<float>(point);
  const float radius_px = static_cast<float>(radius * k.fu) / point.z();
  // Samples one radius apart: an occluder wider than the radius that reaches into the
  // square covers one of them, and the test runs for every line and point of a frame. They
  // lie on the image lattice of multiples of `step`, so that the tests of neighbouring
  // points read the same pixels (few distinct pixels per frame, see DepthImage::source).
  const int step = std::max(1, static_cast<int>(std::ceil(radius_px)));
  const int row_min = std::max(0, lattice_ceil(centre.y() - radius_px, step));
  const int row_max = std::min(depth.depth.rows - 1, static_cast<int>(std::floor(centre.y() + radius_px)));
  const int col_min = std::max(0, lattice_ceil(centre.x() - radius_px, step));
  const int col_max = std::min(depth.depth.cols - 1, static_cast<int>(std::floor(centre.x() + radius_px)));
  const float limit = point.z() - depth_offset - static_cast<float>(threshold);
  for (int row = row_min; row <= row_max; row += step)
    for (int col = col_min; col <= col_max; col += step) {
      const float z = depth.at(row, col);
      if (z > 0.f && z < limit) return true;
    }
  return false;
}

}  // namespace icgp
