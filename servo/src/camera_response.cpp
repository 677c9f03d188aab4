// SPDX-License-Identifier: GPL-2.0-or-later
#include "camera_response.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>

namespace icgp::servo {
namespace {

/// sRGB decoding of the 256 levels, and encoding of linear light in kSteps steps: finer
/// than a level of sRGB anywhere.
struct SrgbTables {
  static constexpr int kSteps = 4096;
  std::array<float, 256> linear{};
  std::array<std::uint8_t, kSteps + 1> encoded{};

  SrgbTables() {
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      linear[i] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    for (int i = 0; i <= kSteps; ++i) {
      const double l = static_cast<double>(i) / kSteps;
      encoded[i] =
          cv::saturate_cast<std::uint8_t>(255.0 * (l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055));
    }
  }
  std::uint8_t encode(float l) const { return encoded[static_cast<int>(std::min(l, 1.f) * kSteps + 0.5f)]; }
};

const SrgbTables& srgb() {
  static const SrgbTables tables;
  return tables;
}

/// The auto-exposure's range of gains: a camera's exposure time and analogue gain span
/// about this much around the nominal exposure.
constexpr double kMinGain = 1.0 / 16.0, kMaxGain = 16.0;

}  // namespace

cv::Mat vignetting_gains(const Intrinsics& k, double v) {
  cv::Mat gains(k.height, k.width, CV_32FC1);
  for (int row = 0; row < k.height; ++row)
    for (int col = 0; col < k.width; ++col) {
      const double x = (col - k.pu) / k.fu, y = (row - k.pv) / k.fv;
      const double cos2 = 1.0 / (1.0 + x * x + y * y);
      gains.at<float>(row, col) = static_cast<float>(1.0 - v * (1.0 - cos2 * cos2));
    }
  return gains;
}

void scale_linear_light(cv::Mat& bgr, const cv::Mat& gains, double gain) {
  const SrgbTables& t = srgb();
  const auto uniform = static_cast<float>(gain);
  for (int row = 0; row < bgr.rows; ++row) {
    auto* pixel = bgr.ptr<cv::Vec3b>(row);
    const float* per_pixel = gains.empty() ? nullptr : gains.ptr<float>(row);
    for (int col = 0; col < bgr.cols; ++col) {
      const float g = per_pixel ? uniform * per_pixel[col] : uniform;
      for (int c = 0; c < 3; ++c) pixel[col][c] = t.encode(t.linear[pixel[col][c]] * g);
    }
  }
}

double mean_linear_light(const cv::Mat& bgr) {
  const SrgbTables& t = srgb();
  double sum = 0.0;
  for (int row = 0; row < bgr.rows; ++row) {
    const auto* pixel = bgr.ptr<cv::Vec3b>(row);
    for (int col = 0; col < bgr.cols; ++col)
      for (int c = 0; c < 3; ++c) sum += t.linear[pixel[col][c]];
  }
  return sum / (3.0 * static_cast<double>(bgr.total()));
}

void AutoExposure::expose(cv::Mat& bgr, double time) {
  if (spec_.target <= 0.0) return;
  // The correction since the last metering: a first-order loop in log exposure.
  if (metered_) {
    const double share = 1.0 - std::exp(-std::max(time - last_time_, 0.0) / spec_.time_constant);
    gain_ = std::clamp(gain_ * std::pow(spec_.target / std::max(metered_mean_, 1e-4), share), kMinGain, kMaxGain);
  }
  scale_linear_light(bgr, cv::Mat(), gain_);
  metered_mean_ = mean_linear_light(bgr);
  last_time_ = time;
  metered_ = true;
}

}  // namespace icgp::servo
