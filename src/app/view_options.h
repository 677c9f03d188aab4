// SPDX-License-Identifier: GPL-2.0-or-later
// A camera looking at a model's origin, described the way a person would ask for it.
#pragma once

#include <CLI/CLI.hpp>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "option_ranges.h"

namespace icgp::app {

struct ViewOptions {
  int width = 640;
  int height = 480;
  double focal = 600.0;      ///< pixels
  double azimuth = 35.0;     ///< degrees about the body y axis (models/ are upright along y)
  double elevation = 25.0;   ///< degrees above the body xz plane
  double distance = 0.0;     ///< metres from the body origin; 0 = frame the object
  double roll = 0.0;         ///< degrees about the optical axis

  Intrinsics intrinsics() const { return Intrinsics::centred(width, height, focal); }

  /// The distance at which an object of this radius spans about 60 % of the shorter side.
  double distance_for(double radius) const {
    return distance > 0.0 ? distance : radius * focal / (0.3 * std::min(width, height));
  }

  Pose camera_T_body(double radius) const {
    const double deg = M_PI / 180.0, az = azimuth * deg, el = elevation * deg;
    const Eigen::Vector3d eye =
        distance_for(radius) * Eigen::Vector3d(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    const Eigen::Vector3d up = std::abs(std::sin(el)) > 0.999 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    const Pose roll_about_axis = Pose::from_rotation_vector(Eigen::Vector3d(0, 0, roll * deg), Eigen::Vector3d::Zero());
    return roll_about_axis * look_at<double>(eye, Eigen::Vector3d::Zero(), up);
  }
};

/// The view's options; check_image_pixels(v.width, v.height, ...) belongs in the command's
/// callback, once both sides are known.
inline void add_view_options(CLI::App& cmd, ViewOptions& v) {
  const yaml::Interval degrees{-360.0, 360.0};
  cmd.add_option("--width", v.width, "Image width in pixels")->check(image_side())->capture_default_str();
  cmd.add_option("--height", v.height, "Image height in pixels")->check(image_side())->capture_default_str();
  cmd.add_option("--focal", v.focal, "Focal length in pixels")->check(number_in(kFocalPx))->capture_default_str();
  cmd.add_option("--azimuth", v.azimuth, "Camera azimuth about the body y axis, degrees")
      ->check(number_in(degrees))
      ->capture_default_str();
  cmd.add_option("--elevation", v.elevation, "Camera elevation, degrees")->check(number_in(degrees))->capture_default_str();
  cmd.add_option("--distance", v.distance, "Camera distance to the body origin, metres (0: frame the object)")
      ->check(number_in({0.0, 1000.0}))
      ->capture_default_str();
  cmd.add_option("--roll", v.roll, "Roll about the optical axis, degrees")->check(number_in(degrees))->capture_default_str();
}

}  // namespace icgp::app
