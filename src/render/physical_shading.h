// SPDX-License-Identifier: GPL-2.0-or-later
// Physically based colour renders (Renderer::set_physical_lighting), private to render/: the
// fragment shader and the lamps' shadow maps. The model is the one Blender's Cycles renders
// the simulated scene with (servo/blender/cycles_server.py), so that the two agree up to
// what a rasteriser cannot do (interreflection, the environment's occlusion).
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "icgp/base/pose.h"

namespace icgp {

/// Lamps a physical render takes at most (shader arrays and texture units).
constexpr int kMaxLamps = 4;

/// The Principled BSDF's dielectric-and-metal model under sun lamps and a uniform ambient
/// environment, in linear light, written sRGB-encoded as a camera's 8-bit output is; it
/// samples textures whose sampler decodes sRGB. Same inputs as the Lambertian shader
/// (camera-frame position, texture coordinates, face normal) and the same colour output
/// location. The shader is written for `lamp_count` (0..kMaxLamps) lamps, those whose bit is
/// set in `shadow_mask` with shadows.
std::string physical_fragment_shader(int lamp_count, unsigned shadow_mask);

/// A body that casts shadows, in the world frame: its bounding sphere is what a lamp's map
/// must cover; its identity and pose tell whether a map drawn earlier still shows it.
struct ShadowCaster {
  int body = 0;
  Pose world_T_body;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< of the bounding sphere, world frame
  double radius = 0.0;
};

/// One depth map per lamp, seen along the lamp's rays (orthographic), fitted to the casters
/// in the world frame: a map stays valid while the lamp and the casters keep still, through
/// a camera's motion (the renders of one motion-blurred frame, a static scene's frames).
class ShadowMaps {
 public:
  /// `size`: texels per side of each map.
  explicit ShadowMaps(int size);
  ~ShadowMaps();
  ShadowMaps(const ShadowMaps&) = delete;
  ShadowMaps& operator=(const ShadowMaps&) = delete;

  /// Whether the lamp's map drawn last shows these casters along this direction to within
  /// half a texel, so that it need not be drawn again.
  bool is_current(int lamp, const Eigen::Vector3d& direction_in_world, const std::vector<ShadowCaster>& casters) const;
  /// Fits the lamp's map to the casters along `direction_in_world`, for drawing it anew.
  /// False when there are no casters (nothing is shadowed).
  bool fit(int lamp, const Eigen::Vector3d& direction_in_world, const std::vector<ShadowCaster>& casters);
  /// The projection of the lamp's map as fitted: world point -> clip coordinates whose
  /// depth is (w - near) / (far - near) in [0, 1] for both of OpenGL's clip conventions.
  Eigen::Matrix4f clip_T_world(int lamp, bool zero_to_one_clip) const;
  /// World point -> (u, v, depth) in [0, 1]^3 of the lamp's map.
  Eigen::Matrix4d map_T_world(int lamp) const;
  /// Metres a texel of the lamp's map spans, and the map's depth range in metres.
  double texel_metres(int lamp) const { return 2.0 * fits_[lamp].half_extent / size_; }
  double depth_range_metres(int lamp) const { return fits_[lamp].far - fits_[lamp].near; }

  /// Binds the lamp's map for drawing depth into it (viewport, cleared depth).
  void begin_drawing(int lamp);
  /// Binds the lamp's map for the shader: its depths to `depth_unit`, their comparison with
  /// a receiver's depth (bilinearly filtered) to `compare_unit`.
  void bind_for_lookup(int lamp, int depth_unit, int compare_unit) const;
  int size() const { return size_; }

 private:
  struct Fit {
    Eigen::Matrix3d light_R_world = Eigen::Matrix3d::Identity();  ///< rows: map u, v, depth axes
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();             ///< of the map, light frame
    double half_extent = 1.0, near = 0.0, far = 1.0;
    bool drawn = false;
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< what the map shows, for is_current
    std::vector<ShadowCaster> casters;
  };
  int size_;
  GLuint fbo_ = 0;
  GLuint textures_[kMaxLamps] = {};
  GLuint depth_sampler_ = 0, compare_sampler_ = 0;
  Fit fits_[kMaxLamps];
};

}  // namespace icgp
