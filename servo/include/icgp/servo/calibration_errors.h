// SPDX-License-Identifier: GPL-2.0-or-later
// The true calibration of a simulated cell, drawn around the nominal one its scenario gives.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// What the cell really is where its calibration says otherwise. The simulator renders and
/// moves with these; the tracker and the control law get the scenario's nominal values.
struct TrueCalibration {
  Intrinsics color, depth;  ///< the cameras' true intrinsics
  double color_k1 = 0.0;    ///< the colour lens's radial distortion (CalibrationErrorSpec::k1)
  Pose depth_T_color;       ///< the true colour camera -> depth camera
  /// Nominal camera -> true camera: on the flange (eye-in-hand, eMc_true = eMc eMc_error), or
  /// of the fixed camera in the arm's base frame (eye-to-hand and grasp).
  Pose camera_error;
  /// Added to the joint angles the arm's encoders report: its true configuration.
  Eigen::Matrix<double, 6, 1> joint_offsets = Eigen::Matrix<double, 6, 1>::Zero();
};

/// `scenario`'s nominal calibration moved by its calibration_error, in signs and directions
/// drawn from `seed` (its own stream: the images' noise does not change with it). Exact (the
/// nominal values) when the scenario gives no error.
TrueCalibration draw_true_calibration(const Scenario& scenario, std::uint64_t seed);

/// The scenario's nominal calibration, taken as true.
TrueCalibration nominal_calibration(const Scenario& scenario);

}  // namespace icgp::servo
