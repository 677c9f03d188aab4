// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <opencv2/core/mat.hpp>

#include "icgp/base/frame.h"

namespace icgp {

/// The measured depth along a colour camera's rays, at a reduced resolution: a depth
/// camera's points moved into the colour camera and splatted nearest-first. Template
/// matching asks it how far the surface is where a template would put the body, so that a
/// template of the wrong size for that distance is not scored there.
class RayDepth {
 public:
  /// Cells across the whole image (4 pixels each in a 640-pixel-wide one).
  static constexpr int kWidth = 160;

  /// Every `step`-th pixel of `depth` in both directions, into a `width`-pixel-wide image
  /// of `color`'s camera (the height follows its aspect ratio).
  RayDepth(const DepthImage& depth, const ColorImage& color, int width = kWidth, int step = 2);

  /// The nearest measured depth within `radius` cells of the colour pixel (u, v) (full
  /// resolution); 0 where nothing is measured there.
  float nearest(double u, double v, int radius = 1) const;

 private:
  Intrinsics color_;  ///< the colour camera at full resolution
  double scale_ = 1.0;  ///< cells per colour pixel
  cv::Mat depth_;       ///< CV_32FC1, metres, 0: none
};

}  // namespace icgp
