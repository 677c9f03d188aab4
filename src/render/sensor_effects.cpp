// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/sensor_effects.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace icgp {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// A depth step this large (relative to Z) between neighbours is a discontinuity.
constexpr float kDiscontinuity = 0.03f;

}  // namespace

void remove_grazing_depth(cv::Mat& depth, const cv::Mat& normals, const Intrinsics& k, double max_angle_deg) {
  if (max_angle_deg >= 90.0) return;
  const double min_cos = std::cos(max_angle_deg * kPi / 180.0);
  for (int r = 0; r < depth.rows; ++r) {
    float* z = depth.ptr<float>(r);
    const cv::Vec3f* normal = normals.ptr<cv::Vec3f>(r);
    for (int c = 0; c < depth.cols; ++c) {
      if (z[c] <= 0.f) continue;
      const cv::Vec3f ray((c - k.pu) / k.fu, (r - k.pv) / k.fv, 1.f);
      if (std::abs(normal[c].dot(ray)) < min_cos * cv::norm(ray)) z[c] = 0.f;
    }
  }
}

void remove_depth_edges(cv::Mat& depth, int radius_px) {
  if (radius_px <= 0) return;
  cv::Mat edges = cv::Mat::zeros(depth.size(), CV_8UC1);
  for (int r = 0; r + 1 < depth.rows; ++r) {
    const float* z = depth.ptr<float>(r);
    const float* below = depth.ptr<float>(r + 1);
    for (int c = 0; c + 1 < depth.cols; ++c) {
      const float nearest = std::min({z[c], z[c + 1], below[c]});
      const float farthest = std::max({z[c], z[c + 1], below[c]});
      if (farthest > 0.f && farthest - nearest > kDiscontinuity * farthest) edges.at<uchar>(r, c) = 255;
    }
  }
  cv::dilate(edges, edges,
             cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * radius_px + 1, 2 * radius_px + 1)));
  depth.setTo(0.f, edges);
}

cv::Mat average_color_renders(int samples, const std::function<cv::Mat(int sample)>& render) {
  if (samples < 1)
    throw std::invalid_argument("motion blur needs at least one render per frame, got " + std::to_string(samples));
  if (samples == 1) return render(0);
  cv::Mat sum;
  for (int i = 0; i < samples; ++i) {
    const cv::Mat image = render(i);
    if (sum.empty()) sum = cv::Mat::zeros(image.size(), CV_32FC3);
    cv::accumulate(image, sum);
  }
  cv::Mat mean;
  sum.convertTo(mean, CV_8UC3, 1.0 / samples);
  return mean;
}

}  // namespace icgp
