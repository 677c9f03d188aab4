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
  // Five samples across the square are enough: occluders are larger than the radius, and
  // the test runs for every line and point of a frame.
  const float step = std::max(1.f, radius_px / 2.f);
  const float limit = point.z() - depth_offset - static_cast<float>(threshold);
  for (float dv = -radius_px; dv <= radius_px + 1e-3f; dv += step) {
    const int row = round_to_int(centre.y() + dv);
    if (row < 0 || row >= depth.depth.rows) continue;
    const float* depth_row = depth.depth.ptr<float>(row);
    for (float du = -radius_px; du <= radius_px + 1e-3f; du += step) {
      const int col = round_to_int(centre.x() + du);
      if (col < 0 || col >= depth.depth.cols) continue;
      const float z = depth_row[col];
      if (z > 0.f && z < limit) return true;
    }
  }
  return false;
}

}  // namespace icgp
