// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "icgp/base/intrinsics.h"
#include "icgp/base/pose.h"
#include "icgp/base/mesh.h"

namespace icgp {

class EglContext;

/// A square image region in pixel-edge coordinates: [u_min, u_min+size) x [v_min, v_min+size).
struct ImageSquare {
  double u_min = 0.0, v_min = 0.0, size = 0.0;
};

/// The square that encloses the projection of a sphere (centre in the camera frame, Z > 0),
/// enlarged by `margin` (a fraction of its size). This is the focused crop of the paper:
/// renders and keypoint detection look only where the object can be.
ImageSquare square_around_sphere(const Intrinsics& intrinsics, const Eigen::Vector3d& centre, double radius,
                                 double margin = 0.1);

/// What a render call should produce; combine with |.
enum RenderTarget : unsigned {
  kRenderDepth = 1u << 0,    ///< CV_32FC1 metric Z in metres, 0 on background
  kRenderNormals = 1u << 1,  ///< CV_32FC3 unit face normals in the camera frame, 0 on background
  kRenderIds = 1u << 2,      ///< CV_8UC1 id of the visible body, 0 on background
  kRenderColor = 1u << 3,    ///< CV_8UC3 BGR shaded colour (textures or material colours)
};

struct RenderOutput {
  cv::Mat depth, normals, ids, color;
};

/// The images of a silhouette render (Renderer::render_silhouette), what model generation
/// reads at every pixel. Depth comes as inverse depth because that is what the depth buffer
/// holds, so it needs no per-pixel conversion, and because its maximum over a region is the
/// nearest surface there, with the background (0) never winning.
struct SilhouetteImages {
  cv::Mat ids;               ///< CV_8UC1 id of the visible body, 0 on background
  cv::Mat inverse_depth;     ///< CV_32FC1 depth_scale / Z (larger is closer), 0 on background
  double depth_scale = 0.0;  ///< metres
  /// Every body pixel lies inside (the projected bounding boxes): work per pixel need not look
  /// further. The images are valid everywhere, zero outside.
  cv::Rect footprint;

  /// Metric Z at a pixel, 0 on background.
  float depth(int row, int col) const {
    const float w = inverse_depth.at<float>(row, col);
    return w > 0.f ? static_cast<float>(depth_scale) / w : 0.f;
  }
};

/// Headlight-style Lambertian shading for colour renders.
struct Lighting {
  Eigen::Vector3f direction_in_camera{0.f, 0.f, 1.f};  ///< direction the light travels
  float ambient = 0.35f;
  float diffuse = 0.65f;
  Eigen::Vector3f background_rgb{0.f, 0.f, 0.f};
};

/// A distant lamp (a sun): parallel rays along one direction.
struct Lamp {
  Eigen::Vector3f direction_in_camera{0.f, 0.f, 1.f};  ///< direction the light travels
  /// What a white Lambertian surface facing it reads (its irradiance over π).
  float strength = 0.65f;
  /// The lamp's apparent diameter (degrees): the softness of its shadows' edges; 0: sharp.
  float angle_deg = 0.f;
};

/// Physically based shading for colour renders, as a path tracer's Principled BSDF gives it
/// in linear light: the materials' roughness, metallic and specular (GGX highlights), the
/// lamps' shadows cast by every visible body that casts shadows, a uniform ambient
/// environment, and the sRGB encoding of a camera's 8-bit output. Textures and
/// Material::diffuse_rgb are read as a path tracer reads them: sRGB-encoded and linear.
struct PhysicalLighting {
  float ambient = 0.35f;     ///< the environment's uniform radiance
  std::vector<Lamp> lamps;   ///< at most 4
  Eigen::Vector3f background_rgb{0.f, 0.f, 0.f};
};

/// Offscreen renderer of rigid bodies for a pinhole camera, exact to the pixel-centre
/// convention of Intrinsics. Owns its EGL context: create and use it on one thread.
class Renderer {
 public:
  using BodyHandle = int;

  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads a mesh. `id` (1..255) is what the id image shows for it; several bodies may
  /// share an id. The body starts at world_T_body = identity.
  BodyHandle add_body(const Mesh& mesh, std::uint8_t id);
  void set_body_pose(BodyHandle body, const Pose& world_T_body);
  /// Hidden bodies are not drawn (and do not occlude).
  void set_body_visible(BodyHandle body, bool visible);
  /// Lambertian colour renders under `lighting` (the default).
  void set_lighting(const Lighting& lighting);
  /// Physically based colour renders under `lighting`, until set_lighting is called. Throws
  /// std::invalid_argument for more than 4 lamps.
  void set_physical_lighting(const PhysicalLighting& lighting);
  /// Whether the body casts shadows in physically based renders (all do at first): a
  /// backdrop that can shade nothing need not widen the lamps' shadow maps.
  void set_body_casts_shadows(BodyHandle body, bool casts_shadows);
  /// Multisample antialiasing of colour renders: `samples` per pixel (0 = off, the
  /// default), so edges blend as a real camera's pixels integrate them. Only the colour
  /// target is affected; depth, normals and ids stay exact per pixel. Throws
  /// std::invalid_argument for 1, a negative count or more than the implementation has
  /// (GL_MAX_SAMPLES), naming the allowed range.
  void set_color_antialiasing(int samples);
  int color_antialiasing() const;

  /// Renders every visible body seen from a camera at camera_T_world with `intrinsics`
  /// (its width/height is the output size). Only the requested targets are filled.
  /// Throws std::invalid_argument for invalid intrinsics.
  RenderOutput render(const Intrinsics& intrinsics, const Pose& camera_T_world, unsigned targets);

  /// Renders only the crop [u_min, u_min+size) x [v_min, v_min+size) of the image that
  /// `intrinsics` describes, resampled to out_size x out_size pixels (a "focused" render
  /// for small, fast per-frame renders). `crop_intrinsics` receives the intrinsics of
  /// the output so pixels can be mapped back.
  RenderOutput render_focused(const Intrinsics& intrinsics, const Pose& camera_T_world, double u_min, double v_min,
                              double size, int out_size, unsigned targets, Intrinsics* crop_intrinsics = nullptr);

  /// Renders the ids and inverse depth of every visible body into `out`, reusing its images
  /// when they already have the size of `intrinsics` (no allocation in a loop of renders).
  /// The same ids and depths as render(kRenderIds | kRenderDepth), several times faster at
  /// model-generation sizes: no shading, depth read straight from the depth buffer, with a
  /// single visible body no id image on the GPU at all, and only the footprint of the
  /// bodies cleared, drawn and read back.
  void render_silhouette(const Intrinsics& intrinsics, const Pose& camera_T_world, SilhouetteImages& out);

  /// How far, in pixels, the scene moves in the image from a camera at camera_T_world to one
  /// at other_camera_T_world: the largest shift of a visible body's bounding-box corner that
  /// the first camera sees in its image (0 when it sees none, as for a backdrop reaching
  /// beyond the image). What motion blur needs to sample.
  double image_motion(const Intrinsics& intrinsics, const Pose& camera_T_world, const Pose& other_camera_T_world) const;

  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace icgp
