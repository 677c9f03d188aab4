// SPDX-License-Identifier: GPL-2.0-or-later
// What the colour camera does to the light that reaches it before its noise: the lens's
// vignetting and the sensor's auto-exposure, both acting on linear light, on images that
// arrive sRGB-encoded from either backend.
#pragma once

#include <opencv2/core/mat.hpp>

#include "icgp/base/intrinsics.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// The lens's vignetting of strength v: each pixel's linear-light gain 1 - v (1 - cos⁴θ),
/// θ its ray's angle off the optical axis (CV_32FC1).
cv::Mat vignetting_gains(const Intrinsics& intrinsics, double v);

/// Scales an sRGB-encoded BGR image (CV_8UC3) in linear light by `gain` times the per-pixel
/// gains (CV_32FC1 of its size; empty: none), saturating at white.
void scale_linear_light(cv::Mat& bgr, const cv::Mat& gains, double gain);

/// The mean linear light (0..1) of an sRGB-encoded BGR image over its pixels and channels.
double mean_linear_light(const cv::Mat& bgr);

/// A camera's auto-exposure: it meters each image it takes (its mean linear light) and
/// corrects the next image's exposure towards the target with a time constant, lagging
/// behind a change of light as a real camera's control loop does.
class AutoExposure {
 public:
  explicit AutoExposure(const AutoExposureSpec& spec) : spec_(spec) {}

  /// Exposes the image taken at `time` (seconds): the gain corrected by what the last image
  /// metered, then meters this one. Does nothing when the spec's target is 0 (fixed
  /// exposure).
  void expose(cv::Mat& bgr, double time);
  double gain() const { return gain_; }

 private:
  AutoExposureSpec spec_;
  double gain_ = 1.0;
  double metered_mean_ = 0.0;  ///< of the last image taken
  double last_time_ = 0.0;
  bool metered_ = false;
};

}  // namespace icgp::servo
