// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/scene_backend.h"

#include <Eigen/Geometry>
#include <cmath>

#include "icgp/base/pose.h"
#include "scene_backends.h"

namespace icgp::servo {

vpHomogeneousMatrix pose_along_motion(const vpHomogeneousMatrix& from, const vpHomogeneousMatrix& to, double fraction) {
  const vpHomogeneousMatrix delta = from.inverse() * to;
  const vpTranslationVector t = delta.getTranslationVector();
  const vpThetaUVector tu(delta.getRotationMatrix());
  const vpHomogeneousMatrix partial(t * fraction, vpThetaUVector(tu[0] * fraction, tu[1] * fraction, tu[2] * fraction));
  return from * partial;
}

LightState light_at(const LightingSpec& lighting, double time) {
  LightState light;
  const Eigen::AngleAxisd turn(lighting.motion_rate * time, lighting.motion_axis.normalized());
  light.direction_in_camera = turn * lighting.direction_in_camera.normalized();
  light.ambient = lighting.ambient;
  light.diffuse =
      lighting.diffuse * (1.0 + lighting.flicker_amplitude * std::sin(2.0 * kPi * lighting.flicker_hz * time));
  return light;
}

std::unique_ptr<SceneBackend> make_scene_backend(const Scenario& scenario, std::uint64_t seed) {
  if (scenario.camera.renderer == RendererKind::kCycles)
    return make_cycles_backend(scenario.camera.cycles, scenario.lighting, seed);
  return make_opengl_backend(scenario.lighting);
}

}  // namespace icgp::servo
