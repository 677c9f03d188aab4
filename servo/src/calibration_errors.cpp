// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/calibration_errors.h"

#include <cmath>

#include "icgp/base/splitmix64.h"

namespace icgp::servo {
namespace {

/// The seed's stream of calibration draws (icgp::seeded_stream purposes are per use).
constexpr std::uint64_t kCalibrationStream = 16;

/// A unit vector of uniformly random direction.
Eigen::Vector3d random_direction(SplitMix64& random) {
  Eigen::Vector3d d;
  do d = Eigen::Vector3d(random.normal(), random.normal(), random.normal());
  while (d.norm() < 1e-9);
  return d.normalized();
}

/// +1 or -1, even odds.
double random_sign(SplitMix64& random) { return random.uniform() < 0.5 ? 1.0 : -1.0; }

/// A rigid motion of `translation` metres and `rotation` radians in random directions.
Pose random_motion(SplitMix64& random, double translation, double rotation) {
  const Eigen::Vector3d t = translation * random_direction(random);
  const Eigen::Vector3d r = rotation * random_direction(random);
  return Pose::from_rotation_vector(r, t);
}

/// `nominal` with its focal lengths scaled by (1 + focal) and its principal point moved by
/// `principal_point` pixels in the direction (cos a, sin a).
Intrinsics moved_intrinsics(const Intrinsics& nominal, double focal, double principal_point, double a) {
  Intrinsics k = nominal;
  k.fu *= 1.0 + focal;
  k.fv *= 1.0 + focal;
  k.pu += principal_point * std::cos(a);
  k.pv += principal_point * std::sin(a);
  return k;
}

}  // namespace

TrueCalibration draw_true_calibration(const Scenario& scenario, std::uint64_t seed) {
  const CalibrationErrorSpec& e = scenario.calibration_error;
  SplitMix64 random = seeded_stream(seed, kCalibrationStream);
  TrueCalibration truth;
  // The colour and depth cameras are calibrated apart: their errors are drawn apart.
  const double color_sign = random_sign(random), depth_sign = random_sign(random);
  const double color_angle = random.uniform(0.0, 2.0 * kPi), depth_angle = random.uniform(0.0, 2.0 * kPi);
  truth.color = moved_intrinsics(scenario.camera.color, color_sign * e.focal, e.principal_point, color_angle);
  truth.depth = moved_intrinsics(scenario.camera.depth, depth_sign * e.focal, e.principal_point, depth_angle);
  truth.color_k1 = e.k1;
  truth.depth_T_color =
      random_motion(random, e.depth_T_color_translation, e.depth_T_color_rotation) * scenario.camera.depth_T_color;
  truth.camera_error = random_motion(random, e.hand_eye_translation, e.hand_eye_rotation);
  for (int i = 0; i < 6; ++i) truth.joint_offsets[i] = random_sign(random) * e.joint_offset;
  return truth;
}

TrueCalibration nominal_calibration(const Scenario& scenario) {
  TrueCalibration truth;
  truth.color = scenario.camera.color;
  truth.depth = scenario.camera.depth;
  truth.depth_T_color = scenario.camera.depth_T_color;
  return truth;
}

}  // namespace icgp::servo
