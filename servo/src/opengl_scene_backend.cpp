// SPDX-License-Identifier: GPL-2.0-or-later
// The OpenGL backend: icgp's own renderer, the one the tracker renders its model with,
// shading physically (PhysicalLighting) as Cycles does.
#include <algorithm>
#include <cmath>

#include "icgp/render/renderer.h"
#include "icgp/render/sensor_effects.h"
#include "icgp/visp/conversions.h"
#include "scene_backends.h"

namespace icgp::servo {
namespace {

/// Renders averaged for motion blur at most, one per pixel the scene moves in the exposure:
/// a still camera's frame costs one render, a fast one's a few.
constexpr int kMaxBlurRenders = 4;

/// Samples per pixel: edges blend as a camera's pixels integrate them. Motion blur's renders
/// take these samples instead, each shifted by a fraction of a pixel (jitter_for).
constexpr int kAntialiasingSamples = 4;

/// The sub-pixel shift of the i-th of n renders of one frame: n points on a circle of
/// 0.4 px around the pixel centre, whose mean is the centre itself (the image does not move);
/// for 4, the rotated grid of 4x multisampling.
Intrinsics jitter_for(Intrinsics k, int i, int n) {
  constexpr double kRadius = 0.395;  // |(1/8, 3/8)| px
  const double angle = std::atan2(-3.0, -1.0) + 2.0 * M_PI * i / n;
  k.pu += kRadius * std::cos(angle);
  k.pv += kRadius * std::sin(angle);
  return k;
}

class OpenGlSceneBackend final : public SceneBackend {
 public:
  OpenGlSceneBackend() = default;

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

  /// Motion blur: the mean of renders along the exposure's part of the motion, one per pixel
  /// the scene moves (at most kMaxBlurRenders), each shifted by a fraction of a pixel so
  /// that together they also antialias; a frame with less than a pixel of motion is one
  /// multisampled render.
  cv::Mat render_color(const Intrinsics& k, const vpHomogeneousMatrix& wMc, const vpHomogeneousMatrix& previous_wMc,
                       double exposure) override {
    const vpHomogeneousMatrix exposure_start = pose_along_motion(wMc, previous_wMc, exposure);
    const double motion_px =
        exposure > 0.0 ? renderer_.image_motion(k, to_pose(wMc.inverse()), to_pose(exposure_start.inverse())) : 0.0;
    const int renders = std::clamp(static_cast<int>(std::ceil(motion_px)), 1, kMaxBlurRenders);
    // The i-th render at the middle of the i-th of `renders` equal parts of the exposure, so
    // that the image is centred where Cycles' continuous blur centres it.
    const auto at_part = [&](int i) { return pose_along_motion(wMc, previous_wMc, exposure * (i + 0.5) / renders); };
    if (renders == 1) {
      renderer_.set_color_antialiasing(kAntialiasingSamples);
      return render_color_at(k, at_part(0));
    }
    renderer_.set_color_antialiasing(0);
    return average_color_renders(renders,
                                 [&](int i) { return render_color_at(jitter_for(k, i, renders), at_part(i)); });
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
