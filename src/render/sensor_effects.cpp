// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/sensor_effects.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "icgp/render/renderer.h"

namespace icgp {
namespace {

/// A depth step this large (relative to Z) between neighbours is a discontinuity.
constexpr float kDiscontinuity = 0.03f;

}  // namespace

void remove_grazing_depth(cv::Mat& depth, const cv::Mat& normals, const Intrinsics& k, double max_angle_deg) {
  if (max_angle_deg >= 90.0) return;
  const double min_cos = std::cos(deg_to_rad(max_angle_deg));
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

SensorNoise SensorNoise::realsense_class() {
  SensorNoise n;
  n.color_sigma = 1.5;
  n.depth_sigma_at_1m = 0.0015;
  n.depth_dropout = 0.05;
  n.grazing_angle_deg = 80.0;
  n.depth_edge_holes_px = 1;
  return n;
}

SensorNoise SensorNoise::kinect_class() {
  SensorNoise n;
  n.color_sigma = 4.0;
  n.depth_sigma_at_1m = 0.005;
  n.depth_dropout = 0.2;
  n.grazing_angle_deg = 75.0;
  n.depth_edge_holes_px = 2;
  return n;
}

cv::Mat sensor_depth(RenderOutput geometry, const Intrinsics& intrinsics, const SensorNoise& noise) {
  if (noise.grazing_angle_deg < 90.0)
    remove_grazing_depth(geometry.depth, geometry.normals, intrinsics, noise.grazing_angle_deg);
  remove_depth_edges(geometry.depth, noise.depth_edge_holes_px);
  return geometry.depth;
}

cv::Mat render_sensor_depth(Renderer& renderer, const Intrinsics& intrinsics, const Pose& camera_T_world,
                            const SensorNoise& noise) {
  const bool grazing_holes = noise.grazing_angle_deg < 90.0;
  return sensor_depth(renderer.render(intrinsics, camera_T_world, kRenderDepth | (grazing_holes ? kRenderNormals : 0u)),
                      intrinsics, noise);
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

void SensorNoiseDraws::add_color_noise(cv::Mat& color, double sigma) {
  if (sigma <= 0.0) return;
  draws_.create(color.size(), CV_16SC3);
  rng_.fill(draws_, cv::RNG::NORMAL, 0.0, sigma);
  cv::add(color, draws_, sum_, cv::noArray(), CV_16SC3);
  sum_.convertTo(color, CV_8UC3);  // saturates
}

void SensorNoiseDraws::add_depth_noise(cv::Mat& depth, const SensorNoise& noise) {
  if (noise.depth_dropout > 0.0) {
    draws_.create(depth.size(), CV_32FC1);
    rng_.fill(draws_, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::compare(draws_, noise.depth_dropout, dropped_, cv::CMP_LT);
    depth.setTo(0.f, dropped_);
  }
  if (noise.depth_sigma_at_1m > 0.0) {
    draws_.create(depth.size(), CV_32FC1);
    rng_.fill(draws_, cv::RNG::NORMAL, 0.0, noise.depth_sigma_at_1m);
    cv::multiply(depth, depth, sum_);
    cv::multiply(draws_, sum_, sum_);
    depth += sum_;  // where depth is 0, Z² is 0: missing stays missing
  }
}

}  // namespace icgp
