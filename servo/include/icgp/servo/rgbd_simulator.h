// SPDX-License-Identifier: GPL-2.0-or-later
// The simulated scene and RGB-D sensor: what the camera on the robot sees at each step.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>

#include "icgp/servo/calibration_errors.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// One capture of the simulated RGB-D sensor, in the shapes ViSP programs hold.
struct RgbdCapture {
  double time = 0.0;                  ///< seconds of simulated time
  bool dropped = false;               ///< the frame was lost: the images are the previous ones
  vpImage<vpRGBa> color;              ///< colour camera "Camera1"
  vpImage<unsigned char> grey;        ///< the same, grey
  vpImage<uint16_t> depth_raw;        ///< depth camera "Camera2", Z = value * depth_scale, 0 = none
  double depth_scale = 1e-4;          ///< metres per unit
  vpHomogeneousMatrix cMo_true;       ///< ground truth, colour camera -> object
  std::optional<vpHomogeneousMatrix> cMg_true;  ///< grasp: ground truth, colour camera -> gripper
};

/// Renders the scenario's scene (object, gripper, background plane, occluder) for the colour
/// and depth cameras with the backend the scenario names (OpenGL, or Blender's Cycles:
/// SceneBackend), and adds the sensor's imperfections (NoiseSpec, lens distortion) from its
/// own seeded generator: the same scenario, seed and camera path give the same images.
/// Throws when the backend cannot start (icgp::RenderError without an OpenGL context,
/// std::runtime_error without Blender).
class RgbdSimulator {
 public:
  /// `world_T_camera`: where the colour camera starts (the background plane faces it);
  /// `world_T_object`: the object's pose in the world at time 0 (initial_world_T_object).
  /// The cameras are exactly as the scenario says.
  RgbdSimulator(const Scenario& scenario, const vpHomogeneousMatrix& world_T_camera,
                const vpHomogeneousMatrix& world_T_object, std::uint64_t seed);
  /// The images are made with `truth`'s intrinsics and depth_T_color; color_camera(),
  /// depth_camera() and depth_M_color() report the scenario's, as a sensor reports its
  /// calibration, not its errors.
  RgbdSimulator(const Scenario& scenario, const TrueCalibration& truth, const vpHomogeneousMatrix& world_T_camera,
                const vpHomogeneousMatrix& world_T_object, std::uint64_t seed);
  ~RgbdSimulator();
  RgbdSimulator(const RgbdSimulator&) = delete;
  RgbdSimulator& operator=(const RgbdSimulator&) = delete;

  /// The object's pose in the world at `time` (moving targets follow ObjectSpec's motion).
  /// Eye-to-hand scenarios give the held pose through `held_object` of capture() instead.
  vpHomogeneousMatrix world_T_object(double time) const;
  /// False while the object is out of the scene (ObjectSpec::removed_for).
  bool object_present(double time) const;

  /// What the sensor sees at `time` with the colour camera at wMc. `previous_wMc` is where
  /// it was at the last capture (motion blur); `held_object`: the object's world pose when a
  /// robot holds it (eye-to-hand); `gripper`: the gripper's world pose (grasp scenarios,
  /// required there). The arm carrying the gripper is not rendered.
  RgbdCapture& capture(double time, const vpHomogeneousMatrix& wMc, const vpHomogeneousMatrix& previous_wMc,
                       const std::optional<vpHomogeneousMatrix>& held_object = std::nullopt,
                       const std::optional<vpHomogeneousMatrix>& gripper = std::nullopt);

  /// The calibration the sensor reports: the scenario's nominal values.
  vpCameraParameters color_camera() const;
  vpCameraParameters depth_camera() const;
  vpHomogeneousMatrix depth_M_color() const;
  /// What the images are made with (the oracles' view of the cell: a tracker gets the above).
  const TrueCalibration& true_calibration() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace icgp::servo
