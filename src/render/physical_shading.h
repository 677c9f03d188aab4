// SPDX-License-Identifier: GPL-2.0-or-later
// Physically based colour renders (Renderer::set_physical_lighting), private to render/: the
// fragment shader and the lamps' shadow maps. The model is the one Blender's Cycles renders
// the simulated scene with (servo/blender/cycles_server.py), so that the two agree up to
// what a rasteriser cannot do (interreflection, the environment's occlusion).
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <Eigen/Geometry>
#include <vector>

namespace icgp {

/// Lamps a physical render takes at most (shader arrays and texture units).
constexpr int kMaxLamps = 4;

/// The Principled BSDF's dielectric-and-metal model under sun lamps and a uniform ambient
/// environment, in linear light, written sRGB-encoded as a camera's 8-bit output is.
/// Same inputs as the Lambertian shader (camera-frame position, texture coordinates, face
/// normal) and the same colour output location.
const char* physical_fragment_shader();

/// A shadow caster's bounding sphere in the camera frame: what a lamp's map must cover.
struct ShadowCaster {
  Eigen::Vector3d centre;
  double radius = 0.0;
};

/// One depth map per lamp, seen along the lamp's rays (orthographic), fitted to the casters.
class ShadowMaps {
 public:
  /// `size`: texels per side of each map.
  explicit ShadowMaps(int size);
  ~ShadowMaps();
  ShadowMaps(const ShadowMaps&) = delete;
  ShadowMaps& operator=(const ShadowMaps&) = delete;

  /// What a lamp's map shows: the fit of the casters along `direction_in_camera`. False when
  /// there are no casters (nothing is shadowed).
  bool fit(int lamp, const Eigen::Vector3d& direction_in_camera, const std::vector<ShadowCaster>& casters);
  /// The projection of the lamp's map as fitted: camera-frame point -> clip coordinates whose
  /// depth is (w - near) / (far - near) in [0, 1] for both of OpenGL's clip conventions.
  Eigen::Matrix4f clip_T_camera(int lamp, bool zero_to_one_clip) const;
  /// Camera-frame point -> (u, v, depth) in [0, 1]^3 of the lamp's map.
  Eigen::Matrix4f map_T_camera(int lamp) const;
  /// Metres a texel of the lamp's map spans, and the map's depth range in metres.
  float texel_metres(int lamp) const { return static_cast<float>(2.0 * fits_[lamp].half_extent / size_); }
  float depth_range_metres(int lamp) const { return static_cast<float>(fits_[lamp].far - fits_[lamp].near); }

  /// Binds the lamp's map for drawing depth into it (viewport, cleared depth).
  void begin_drawing(int lamp);
  GLuint texture(int lamp) const { return textures_[lamp]; }
  int size() const { return size_; }

 private:
  struct Fit {
    Eigen::Matrix3d light_R_camera = Eigen::Matrix3d::Identity();  ///< rows: map u, v, depth axes
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();              ///< of the map, light frame
    double half_extent = 1.0, near = 0.0, far = 1.0;
  };
  int size_;
  GLuint fbo_ = 0;
  GLuint textures_[kMaxLamps] = {};
  Fit fits_[kMaxLamps];
};

}  // namespace icgp
