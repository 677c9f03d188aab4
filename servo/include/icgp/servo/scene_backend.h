// SPDX-License-Identifier: GPL-2.0-or-later
// What makes the simulated camera's images: the OpenGL rasteriser or Blender's Cycles path
// tracer, behind one interface, so that the sensor model around them is the same.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <visp3/core/vpHomogeneousMatrix.h>

#include "icgp/base/intrinsics.h"
#include "icgp/base/mesh.h"
#include "icgp/base/pose.h"
#include "icgp/render/renderer.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// The scene's light at one moment (LightingSpec at a time).
struct LightState {
  Eigen::Vector3d direction_in_camera{0.0, 0.0, 1.0};  ///< unit, the direction the light travels
  double ambient = 0.35;
  double diffuse = 0.65;
};

/// The light of `lighting` at `time` seconds: its direction turned about its motion axis,
/// its strength (diffuse) flickering; ambient light stays.
LightState light_at(const LightingSpec& lighting, double time);

/// The scene's bodies, posed step by step, seen through an exact pinhole. The sensor's
/// imperfections (noise, depth holes, lens distortion) are the simulator's, not the backend's.
class SceneBackend {
 public:
  using BodyHandle = int;

  virtual ~SceneBackend() = default;

  /// Adds a body at world_T_body = identity; `id` tells bodies apart where the backend
  /// has id images.
  virtual BodyHandle add_body(const Mesh& mesh, std::uint8_t id) = 0;
  virtual void set_body_pose(BodyHandle body, const Pose& world_T_body) = 0;
  /// Hidden bodies are not seen and cast nothing.
  virtual void set_body_visible(BodyHandle body, bool visible) = 0;

  /// The light of the next colour renders (the backend starts with the scenario's at time 0).
  virtual void set_light(const LightState& light) = 0;

  /// The colour image (CV_8UC3 BGR) of the camera now at wMc. `exposure` (0..1) is the
  /// fraction of its motion from previous_wMc, the last part, that the image integrates
  /// (motion blur; 0: sharp).
  virtual cv::Mat render_color(const Intrinsics& intrinsics, const vpHomogeneousMatrix& wMc,
                               const vpHomogeneousMatrix& previous_wMc, double exposure) = 0;
  /// The exact geometry seen from camera_T_world: depth (CV_32FC1 metric Z, 0 where nothing
  /// is) and, when asked, unit camera-frame normals (CV_32FC3), each pixel the surface
  /// through its centre.
  virtual RenderOutput render_geometry(const Intrinsics& intrinsics, const Pose& camera_T_world,
                                       bool with_normals) = 0;
};

/// The backend the scenario's camera asks for (CameraSpec::renderer), lit by its lighting.
/// `seed` makes a path tracer's sampling noise reproducible. Throws std::runtime_error when
/// it cannot start (no OpenGL context, no Blender).
std::unique_ptr<SceneBackend> make_scene_backend(const Scenario& scenario, std::uint64_t seed);

}  // namespace icgp::servo
