// SPDX-License-Identifier: GPL-2.0-or-later
// The OpenGL backend: icgp's own renderer, the one the tracker renders its model with.
#include "icgp/render/renderer.h"
#include "icgp/render/sensor_effects.h"
#include "icgp/visp/conversions.h"
#include "scene_backends.h"

namespace icgp::servo {
namespace {

/// Renders averaged for motion blur.
constexpr int kBlurSamples = 4;

class OpenGlSceneBackend final : public SceneBackend {
 public:
  explicit OpenGlSceneBackend(const LightingSpec& spec) { set_light(light_at(spec, 0.0)); }

  void set_light(const LightState& light) override {
    Lighting lighting;
    lighting.direction_in_camera = light.direction_in_camera.cast<float>();
    lighting.ambient = static_cast<float>(light.ambient);
    lighting.diffuse = static_cast<float>(light.diffuse);
    renderer_.set_lighting(lighting);
  }

  BodyHandle add_body(const Mesh& mesh, std::uint8_t id) override { return renderer_.add_body(mesh, id); }
  void set_body_pose(BodyHandle body, const Pose& world_T_body) override { renderer_.set_body_pose(body, world_T_body); }
  void set_body_visible(BodyHandle body, bool visible) override { renderer_.set_body_visible(body, visible); }

  /// Motion blur: the mean of renders along the exposure's part of the motion.
  cv::Mat render_color(const Intrinsics& k, const vpHomogeneousMatrix& wMc, const vpHomogeneousMatrix& previous_wMc,
                       double exposure) override {
    if (exposure <= 0.0) return renderer_.render(k, to_pose(wMc.inverse()), kRenderColor).color;
    return average_color_renders(kBlurSamples, [&](int i) {
      const double back = exposure * i / kBlurSamples;  // fraction of the step before the capture
      const vpHomogeneousMatrix pose = pose_along_motion(wMc, previous_wMc, back);
      return renderer_.render(k, to_pose(pose.inverse()), kRenderColor).color;
    });
  }

  RenderOutput render_geometry(const Intrinsics& k, const Pose& camera_T_world, bool with_normals) override {
    return renderer_.render(k, camera_T_world, kRenderDepth | (with_normals ? kRenderNormals : 0u));
  }

 private:
  Renderer renderer_;
};

}  // namespace

std::unique_ptr<SceneBackend> make_opengl_backend(const LightingSpec& lighting) {
  return std::make_unique<OpenGlSceneBackend>(lighting);
}

}  // namespace icgp::servo
