// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/scene_backend.h"

#include <Eigen/Geometry>
#include <cmath>

#include "icgp/base/pose.h"
#include "icgp/visp/conversions.h"
#include "scene_backends.h"

namespace icgp::servo {

vpHomogeneousMatrix pose_along_motion(const vpHomogeneousMatrix& from, const vpHomogeneousMatrix& to, double fraction) {
  const vpHomogeneousMatrix delta = from.inverse() * to;
  const vpTranslationVector t = delta.getTranslationVector();
  const vpThetaUVector tu(delta.getRotationMatrix());
  const vpHomogeneousMatrix partial(t * fraction, vpThetaUVector(tu[0] * fraction, tu[1] * fraction, tu[2] * fraction));
  return from * partial;
}

std::vector<Eigen::Vector3d> LightState::directions_in_camera(const vpHomogeneousMatrix& wMc) const {
  const Eigen::Matrix3d camera_R_world = to_pose(wMc).rotation().transpose();
  std::vector<Eigen::Vector3d> directions;
  for (const LampState& lamp : lamps)
    directions.push_back(lamp.fixed_to_camera ? lamp.direction : camera_R_world * lamp.direction);
  return directions;
}

LightState light_at(const LightingSpec& lighting, double time, const Eigen::Matrix3d& world_R_start_camera) {
  // Mains-powered lamps flicker together.
  const double flicker = 1.0 + lighting.flicker_amplitude * std::sin(2.0 * kPi * lighting.flicker_hz * time);
  const Eigen::AngleAxisd turn(lighting.motion_rate * time, lighting.motion_axis.normalized());
  LightState light;
  light.ambient = lighting.ambient;
  light.lamps = {{turn * lighting.direction_in_camera.normalized(), true, lighting.diffuse * flicker}};
  for (const SceneLampSpec& lamp : lighting.scene_lamps)
    light.lamps.push_back({world_R_start_camera * lamp.direction_in_start_camera.normalized(), false,
                           lamp.strength * flicker});
  return light;
}

std::unique_ptr<SceneBackend> make_scene_backend(const Scenario& scenario, std::uint64_t seed) {
  if (scenario.camera.renderer == RendererKind::kCycles)
    return make_cycles_backend(scenario.camera.cycles, seed);
  return make_opengl_backend();
}

}  // namespace icgp::servo
