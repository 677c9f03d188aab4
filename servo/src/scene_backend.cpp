// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/servo/scene_backend.h"

#include "scene_backends.h"

namespace icgp::servo {

vpHomogeneousMatrix pose_along_motion(const vpHomogeneousMatrix& from, const vpHomogeneousMatrix& to, double fraction) {
  const vpHomogeneousMatrix delta = from.inverse() * to;
  const vpTranslationVector t = delta.getTranslationVector();
  const vpThetaUVector tu(delta.getRotationMatrix());
  const vpHomogeneousMatrix partial(t * fraction, vpThetaUVector(tu[0] * fraction, tu[1] * fraction, tu[2] * fraction));
  return from * partial;
}

std::unique_ptr<SceneBackend> make_scene_backend(const Scenario& scenario, std::uint64_t seed) {
  if (scenario.camera.renderer == RendererKind::kCycles)
    return make_cycles_backend(scenario.camera.cycles, scenario.lighting, seed);
  return make_opengl_backend(scenario.lighting);
}

}  // namespace icgp::servo
