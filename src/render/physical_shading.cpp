// SPDX-License-Identifier: GPL-2.0-or-later
#include "physical_shading.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "icgp/render/egl_context.h"

namespace icgp {

// Blender's Principled BSDF (version 1, Blender 3.4) as a rasteriser can evaluate it:
// * diffuse: the base colour times (1 - metallic), Lambertian;
// * specular: GGX microfacets (alpha = roughness²) with Smith's masking and Schlick's
//   Fresnel from F0 = 0.08 specular for a dielectric, the base colour for a metal;
// * a sun lamp of strength S gives irradiance π S, so that a white Lambertian surface
//   facing it reads S, as in the Lambertian shader;
// * the uniform ambient environment is integrated exactly for diffuse, and by Karis'
//   analytic fit of the split-sum environment BRDF for specular;
// * sun lamps of a few degrees cast soft shadows: percentage-closer filtering over the
//   penumbra the lamp's disc projects across the gap from blocker to receiver.
// Version 4.00 for sampler arrays indexed in a loop.
const char* physical_fragment_shader() {
  return R"(#version 400 core
in vec3 f_camera_position;
in vec2 f_texcoord;
flat in vec3 f_normal;
uniform bool has_texture;
uniform sampler2D diffuse_texture;
uniform vec3 diffuse_rgb;
uniform float roughness;
uniform float metallic;
uniform float specular;
uniform float ambient;
uniform int lamp_count;
uniform vec3 lamp_direction[4];
uniform float lamp_strength[4];
uniform bool lamp_has_shadow[4];
uniform mat4 lamp_map_T_camera[4];
uniform float lamp_texel[4];          // a texel, in map units
uniform float lamp_spread[4];         // penumbra radius (map units) per unit of map depth
uniform float lamp_normal_offset[4];  // metres
uniform sampler2D lamp_shadow[4];
layout(location = 3) out vec4 out_color;

const float PI = 3.14159265358979;

vec3 srgb_to_linear(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c)); }
vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

float ggx(float nh, float a2) {
  float d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}
float smith(float nx, float a2) { return 2.0 * nx / (nx + sqrt(a2 + (1.0 - a2) * nx * nx)); }

// Whether a map texel of depth d holds a caster nearer the lamp than `depth`. The map is
// cleared to 1, beyond every caster, while receivers may lie further still.
bool blocks(float d, float depth) { return d < 1.0 && d < depth; }

// The fraction of lamp i's disc seen from p (normal n): 1 unshadowed, 0 in the umbra.
float lit_fraction(int i, vec3 p, vec3 n) {
  if (!lamp_has_shadow[i]) return 1.0;
  vec3 m = (lamp_map_T_camera[i] * vec4(p + lamp_normal_offset[i] * n, 1.0)).xyz;
  if (any(lessThan(m.xy, vec2(0.0))) || any(greaterThan(m.xy, vec2(1.0)))) return 1.0;
  float bias = 2.0 * lamp_texel[i];
  float search = max(lamp_spread[i] * m.z, lamp_texel[i]);
  float blockers = 0.0, blocker_depth = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      float d = texture(lamp_shadow[i], m.xy + vec2(x, y) * search).r;
      if (blocks(d, m.z - bias)) {
        blockers += 1.0;
        blocker_depth += d;
      }
    }
  if (blockers == 0.0) return 1.0;
  float radius = max(lamp_spread[i] * (m.z - blocker_depth / blockers), lamp_texel[i]);
  float lit = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x)
      lit += blocks(texture(lamp_shadow[i], m.xy + vec2(x, y) * radius).r, m.z - bias) ? 0.0 : 1.0;
  return lit / 9.0;
}

void main() {
  // Texture rows are uploaded top row first, texture coordinates have v up.
  vec3 base = has_texture ? srgb_to_linear(texture(diffuse_texture, vec2(f_texcoord.x, 1.0 - f_texcoord.y)).rgb)
                          : diffuse_rgb;
  vec3 n = f_normal;
  vec3 v = normalize(-f_camera_position);
  float nv = max(dot(n, v), 1e-4);
  float alpha = max(roughness * roughness, 1e-3);
  float a2 = alpha * alpha;
  vec3 f0 = mix(vec3(0.08 * specular), base, metallic);
  vec3 diffuse_color = base * (1.0 - metallic);

  vec4 r = roughness * vec4(-1.0, -0.0275, -0.572, 0.022) + vec4(1.0, 0.0425, 1.04, -0.04);
  float a004 = min(r.x * r.x, exp2(-9.28 * nv)) * r.x + r.y;
  vec2 environment = vec2(-1.04, 1.04) * a004 + r.zw;
  vec3 color = ambient * (diffuse_color + f0 * environment.x + environment.y);

  for (int i = 0; i < lamp_count; ++i) {
    vec3 l = -lamp_direction[i];
    float nl = dot(n, l);
    if (nl <= 0.0 || lamp_strength[i] <= 0.0) continue;
    vec3 h = normalize(l + v);
    float vh = max(dot(v, h), 0.0);
    vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vh, 5.0);
    vec3 specular_brdf = ggx(max(dot(n, h), 0.0), a2) * smith(nl, a2) * smith(nv, a2) * fresnel / (4.0 * nl * nv);
    color += (diffuse_color + PI * specular_brdf) * lamp_strength[i] * nl * lit_fraction(i, f_camera_position, n);
  }
  out_color = vec4(linear_to_srgb(color), 1.0);
}
)";
}

ShadowMaps::ShadowMaps(int size) : size_(size) {
  glGenFramebuffers(1, &fbo_);
  glGenTextures(kMaxLamps, textures_);
  for (GLuint texture : textures_) {
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

ShadowMaps::~ShadowMaps() {
  glDeleteTextures(kMaxLamps, textures_);
  glDeleteFramebuffers(1, &fbo_);
}

bool ShadowMaps::fit(int lamp, const Eigen::Vector3d& direction_in_camera, const std::vector<ShadowCaster>& casters) {
  if (casters.empty()) return false;
  Fit& f = fits_[lamp];
  const Eigen::Vector3d w = direction_in_camera.normalized();
  const Eigen::Vector3d u = w.unitOrthogonal();
  f.light_R_camera.row(0) = u.transpose();
  f.light_R_camera.row(1) = w.cross(u).transpose();
  f.light_R_camera.row(2) = w.transpose();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const ShadowCaster& c : casters) {
    const Eigen::Vector3d p = f.light_R_camera * c.centre;
    lo = lo.cwiseMin((p.array() - c.radius).matrix());
    hi = hi.cwiseMax((p.array() + c.radius).matrix());
  }
  f.centre = 0.5 * (lo + hi).head<2>();
  f.half_extent = 0.5 * (hi - lo).head<2>().maxCoeff() * 1.01;
  const double margin = 0.01 * (hi.z() - lo.z());
  f.near = lo.z() - margin;
  f.far = hi.z() + margin;
  return true;
}

Eigen::Matrix4f ShadowMaps::map_T_camera(int lamp) const {
  const Fit& f = fits_[lamp];
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  const double to_map = 0.5 / f.half_extent, depth = 1.0 / (f.far - f.near);
  m.block<2, 3>(0, 0) = to_map * f.light_R_camera.topRows<2>();
  m.block<2, 1>(0, 3) = Eigen::Vector2d::Constant(0.5) - to_map * f.centre;
  m.block<1, 3>(2, 0) = depth * f.light_R_camera.row(2);
  m(2, 3) = -depth * f.near;
  return m.cast<float>();
}

Eigen::Matrix4f ShadowMaps::clip_T_camera(int lamp, bool zero_to_one_clip) const {
  Eigen::Matrix4f clip_T_map = Eigen::Matrix4f::Identity();
  clip_T_map.block<2, 2>(0, 0) *= 2.f;
  clip_T_map.block<2, 1>(0, 3).setConstant(-1.f);
  if (!zero_to_one_clip) clip_T_map(2, 2) = 2.f, clip_T_map(2, 3) = -1.f;
  return clip_T_map * map_T_camera(lamp);
}

void ShadowMaps::begin_drawing(int lamp) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, textures_[lamp], 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RenderError("shadow map framebuffer of " + std::to_string(size_) + "x" + std::to_string(size_) +
                      " is incomplete");
  glViewport(0, 0, size_, size_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDepthFunc(GL_LESS);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
}

}  // namespace icgp
