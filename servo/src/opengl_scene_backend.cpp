// SPDX-License-Identifier: GPL-2.0-or-later
// The OpenGL backend: icgp's own renderer, the one the tracker renders its model with,
// shading physically (PhysicalLighting) as Cycles does.
#include "icgp/render/renderer.h"
#include "icgp/render/sensor_effects.h"
#include "icgp/visp/conversions.h"
#include "scene_backends.h"

namespace icgp::servo {
namespace {

/// Renders averaged for motion blur.
constexpr int kBlurSamples = 4;

/// Samples per pixel: edges blend as a camera's pixels integrate them.
constexpr int kAntialiasingSamples = 4;

class OpenGlSceneBackend final : public SceneBackend {
 public:
  OpenGlSceneBackend() { renderer_.set_color_antialiasing(kAntialiasingSamples); }

  void set_light(const LightState& light) override { light_ = light; }

  BodyHandle add_body(const Mesh& mesh, std::uint8_t id) override { return renderer_.add_body(mesh, id); }
  /// Out of the lamps' shadow maps, which then span only what can cast a visible shadow.
  BodyHandle add_backdrop(const Mesh& mesh, std::uint8_t id) override {
    const BodyHandle body = renderer_.add_body(mesh, id);
    renderer_.set_body_casts_shadows(body, false);
    return body;
  }
  void set_body_pose(BodyHandle body, const Pose& world_T_body) override { renderer_.set_body_pose(body, world_T_body); }
  void set_body_visible(BodyHandle body, bool visible) override { renderer_.set_body_visible(body, visible); }

  /// Motion blur: the mean of renders along the exposure's part of the motion.
  cv::Mat render_color(const Intrinsics& k, const vpHomogeneousMatrix& wMc, const vpHomogeneousMatrix& previous_wMc,
                       double exposure) override {
    if (exposure <= 0.0) return render_color_at(k, wMc);
    return average_color_renders(kBlurSamples, [&](int i) {
      const double back = exposure * i / kBlurSamples;  // fraction of the step before the capture
      return render_color_at(k, pose_along_motion(wMc, previous_wMc, back));
    });
  }

  RenderOutput render_geometry(const Intrinsics& k, const Pose& camera_T_world, bool with_normals) override {
    return renderer_.render(k, camera_T_world, kRenderDepth | (with_normals ? kRenderNormals : 0u));
  }

 private:
  /// The colour render of a camera at wMc: the camera's lamp moves with it through an
  /// exposure, the scene's lamps stay where they are.
  cv::Mat render_color_at(const Intrinsics& k, const vpHomogeneousMatrix& wMc) {
    PhysicalLighting lighting;
    lighting.ambient = static_cast<float>(light_.ambient);
    const std::vector<Eigen::Vector3d> directions = light_.directions_in_camera(wMc);
    for (std::size_t i = 0; i < directions.size(); ++i)
      lighting.lamps.push_back({directions[i].cast<float>(), static_cast<float>(light_.lamps[i].strength),
                                static_cast<float>(kLampAngleDeg)});
    renderer_.set_physical_lighting(lighting);
    return renderer_.render(k, to_pose(wMc.inverse()), kRenderColor).color;
  }

  Renderer renderer_;
  LightState light_;
};

}  // namespace

std::unique_ptr<SceneBackend> make_opengl_backend() {
  return std::make_unique<OpenGlSceneBackend>();
}

}  // namespace icgp::servo
