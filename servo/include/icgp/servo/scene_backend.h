// SPDX-License-Identifier: GPL-2.0-or-later
// What makes the simulated camera's images: the OpenGL rasteriser or Blender's Cycles path
// tracer, behind one interface, so that the sensor model around them is the same.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>
#include <opencv2/core/mat.hpp>
#include <visp3/core/vpHomogeneousMatrix.h>

#include "icgp/base/intrinsics.h"
#include "icgp/base/mesh.h"
#include "icgp/base/pose.h"
#include "icgp/render/renderer.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// Lamps' apparent diameter (degrees), in both backends: a lamp a few metres away casts
/// shadows with soft edges, as a real cell's do.
constexpr double kLampAngleDeg = 2.0;

/// One lamp (a sun: parallel rays) at one moment.
struct LampState {
  Eigen::Vector3d direction{0.0, 0.0, 1.0};  ///< unit, the direction its light travels
  /// `direction` is in the camera frame (a light on the camera); otherwise in the world frame.
  bool fixed_to_camera = true;
  double strength = 0.65;  ///< what a white Lambertian surface facing it reads
};

/// The scene's light at one moment (LightingSpec at a time).
struct LightState {
  std::vector<LampState> lamps{LampState{}};
  double ambient = 0.35;  ///< a uniform environment's radiance

  /// The lamps' directions in the frame of the camera at wMc.
  std::vector<Eigen::Vector3d> directions_in_camera(const vpHomogeneousMatrix& wMc) const;
};

/// The light of `lighting` at `time` seconds: the camera's lamp turned about its motion axis,
/// every lamp's strength flickering, ambient light steady. The scene's lamps are given in
/// the frame of the camera at its start, which is at world_R_start_camera.
LightState light_at(const LightingSpec& lighting, double time, const Eigen::Matrix3d& world_R_start_camera);

/// The scene's bodies, posed step by step, seen through an exact pinhole. The sensor's
/// imperfections (noise, depth holes, lens distortion) are the simulator's, not the backend's.
class SceneBackend {
 public:
  using BodyHandle = int;

  virtual ~SceneBackend() = default;

  /// Adds a body at world_T_body = identity; `id` tells bodies apart where the backend
  /// has id images.
  virtual BodyHandle add_body(const Mesh& mesh, std::uint8_t id) = 0;
  /// Adds a body that stands behind all others (a wall, a table): it receives their shadows
  /// and casts none where the camera could see them.
  virtual BodyHandle add_backdrop(const Mesh& mesh, std::uint8_t id) = 0;
  virtual void set_body_pose(BodyHandle body, const Pose& world_T_body) = 0;
  /// Hidden bodies are not seen and cast nothing.
  virtual void set_body_visible(BodyHandle body, bool visible) = 0;

  /// The light of the next colour renders (the backend starts with LightState's defaults).
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

/// The backend the scenario's camera asks for (CameraSpec::renderer).
/// `seed` makes a path tracer's sampling noise reproducible. Throws std::runtime_error when
/// it cannot start (no OpenGL context, no Blender).
std::unique_ptr<SceneBackend> make_scene_backend(const Scenario& scenario, std::uint64_t seed);

}  // namespace icgp::servo
