// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/ray_depth.h"

#include <algorithm>
#include <cmath>

namespace icgp {

RayDepth::RayDepth(const DepthImage& depth, const ColorImage& color, int width, int step)
    : color_(color.intrinsics), scale_(static_cast<double>(width) / std::max(1, color.intrinsics.width)) {
  const int height = std::max(1, static_cast<int>(std::lround(color.intrinsics.height * scale_)));
  depth_ = cv::Mat(height, width, CV_32F, cv::Scalar(0.f));
  const Pose color_T_depth = color.camera_T_reference * depth.camera_T_reference.inverse();
  for (int row = 0; row < depth.depth.rows; row += step)
    for (int col = 0; col < depth.depth.cols; col += step) {
      const float z = depth.at(row, col);
      if (!(z > 0.f)) continue;
      const Eigen::Vector3d X = color_T_depth * depth.point(row, col, z).cast<double>();
      if (X.z() <= 0.0) continue;
      const Eigen::Vector2d uv = color_.project(X);
      const int c = static_cast<int>(std::lround((uv.x() + 0.5) * scale_ - 0.5));
      const int r = static_cast<int>(std::lround((uv.y() + 0.5) * scale_ - 0.5));
      if (c < 0 || r < 0 || c >= depth_.cols || r >= depth_.rows) continue;
      float& cell = depth_.at<float>(r, c);
      const float Z = static_cast<float>(X.z());
      if (cell == 0.f || Z < cell) cell = Z;
    }
}

float RayDepth::nearest(double u, double v, int radius) const {
  const int c = static_cast<int>(std::lround((u + 0.5) * scale_ - 0.5));
  const int r = static_cast<int>(std::lround((v + 0.5) * scale_ - 0.5));
  float best = 0.f;
  for (int i = std::max(0, r - radius); i <= std::min(depth_.rows - 1, r + radius); ++i)
    for (int j = std::max(0, c - radius); j <= std::min(depth_.cols - 1, c + radius); ++j) {
      const float z = depth_.at<float>(i, j);
      if (z > 0.f && (best == 0.f || z < best)) best = z;
    }
  return best;
}

}  // namespace icgp
