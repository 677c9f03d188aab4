// SPDX-License-Identifier: GPL-2.0-or-later
// What a real RGB-D sensor does to rendered images that a renderer alone does not: its
// parameters (SensorNoise), depth holes at grazing angles and along depth edges, random
// noise and dropout (SensorNoiseDraws), and motion blur. Shared by the sequence writer and
// the servo simulator so that both simulate the same sensor with the same parameters and
// the same code.
#pragma once

#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"

namespace icgp {

class Renderer;
struct RenderOutput;

/// Sensor imperfections added to the rendered images. Zero = exact renders.
struct SensorNoise {
  double color_sigma = 0.0;        ///< Gaussian noise on each colour channel, 8-bit levels
  /// Depth noise sigma = this * Z^2 (metres at 1 m): stereo and structured-light sensors'
  /// error grows with the square of the distance.
  double depth_sigma_at_1m = 0.0;
  double depth_dropout = 0.0;  ///< fraction of depth pixels randomly reported as missing (0)
  /// Depth is missing where the surface is seen more obliquely than this (angle between its
  /// normal and the viewing ray, degrees); 90 = never.
  double grazing_angle_deg = 90.0;
  /// Depth is missing within this many pixels of a depth discontinuity; 0 = never.
  int depth_edge_holes_px = 0;

  /// A RealSense-class active stereo sensor: sigma 0.0015 Z^2, 5 % dropout, holes along
  /// depth edges (1 px) and beyond 80 deg, mild colour noise.
  static SensorNoise realsense_class();
  /// A Kinect-class structured-light sensor: sigma 0.005 Z^2, 20 % dropout, holes along
  /// depth edges (2 px) and beyond 75 deg, visible colour noise.
  static SensorNoise kinect_class();
};


/// The random part of a sensor's imperfections, drawn whole images at a time from one
/// seeded stream (OpenCV's generator): the same seed gives the same images, bit for bit.
class SensorNoiseDraws {
 public:
  explicit SensorNoiseDraws(std::uint64_t seed) : rng_(seed) {}

  /// Adds Gaussian noise of `sigma` 8-bit levels to each channel of a CV_8UC3 image,
  /// saturated to [0, 255]; nothing for sigma 0.
  void add_color_noise(cv::Mat& color, double sigma);
  /// Drops each measured pixel of a CV_32FC1 depth image with probability
  /// noise.depth_dropout (0: no measurement), then adds Gaussian noise of
  /// noise.depth_sigma_at_1m · Z² to the others.
  void add_depth_noise(cv::Mat& depth, const SensorNoise& noise);
  /// A uniform draw in [0, 1) from the same stream (e.g. whether a frame is dropped).
  double uniform() { return rng_.uniform(0.0, 1.0); }

 private:
  cv::RNG rng_;
  cv::Mat draws_, sum_, dropped_;  ///< kept from image to image: no allocation per frame
};

/// Removes depth (sets 0) where the surface is seen more obliquely than `max_angle_deg`
/// (angle between its normal and the viewing ray), as structured-light and stereo sensors
/// lose it there. `normals`: CV_32FC3 camera-frame normals of the same render; `intrinsics`
/// of the depth image. Nothing happens for angles of 90 degrees or more.
void remove_grazing_depth(cv::Mat& depth, const cv::Mat& normals, const Intrinsics& intrinsics, double max_angle_deg);

/// Removes depth within `radius_px` pixels of a depth discontinuity (a step of more than 3 %
/// of Z between neighbours, or an edge against missing depth), where real sensors report
/// nothing or "flying pixels" between the two surfaces. Nothing happens for radius 0.
void remove_depth_edges(cv::Mat& depth, int radius_px);

/// The depth image (CV_32FC1 metric Z, 0 = none) a sensor measures before its random noise,
/// from a render's depth (and normals, when noise.grazing_angle_deg < 90): the render without
/// the surfaces seen more obliquely than noise.grazing_angle_deg (remove_grazing_depth) and
/// without depth within noise.depth_edge_holes_px of a discontinuity (remove_depth_edges).
cv::Mat sensor_depth(RenderOutput geometry, const Intrinsics& intrinsics, const SensorNoise& noise);

/// sensor_depth of `renderer`'s scene seen from camera_T_world.
cv::Mat render_sensor_depth(Renderer& renderer, const Intrinsics& intrinsics, const Pose& camera_T_world,
                            const SensorNoise& noise);

/// Motion blur: the mean of `samples` CV_8UC3 colour renders, `render(i)` being the image
/// at the i-th instant of the exposure (i = 0 .. samples-1), rounded to 8 bits. One sample
/// returns that render unchanged. Throws std::invalid_argument for samples < 1.
cv::Mat average_color_renders(int samples, const std::function<cv::Mat(int sample)>& render);

}  // namespace icgp
