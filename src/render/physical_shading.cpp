// SPDX-License-Identifier: GPL-2.0-or-later
#include "physical_shading.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "icgp/render/egl_context.h"

namespace icgp {

// Blender's Principled BSDF (version 1, Blender 3.4) as a rasteriser can evaluate it, in
// linear light; textures are sampled from sRGB textures, which the sampler decodes:
// * diffuse: the base colour times (1 - metallic), Lambertian;
// * specular: GGX microfacets (alpha = roughness²) with Smith's masking and Schlick's
//   Fresnel from F0 = 0.08 specular for a dielectric, the base colour for a metal;
// * a sun lamp of strength S gives irradiance π S, so that a white Lambertian surface
//   facing it reads S, as in the Lambertian shader;
// * the uniform ambient environment is integrated exactly for diffuse, and by Karis'
//   analytic fit of the split-sum environment BRDF for specular;
// * sun lamps of a few degrees cast soft shadows: percentage-closer filtering over the
//   penumbra the lamp's disc projects across the gap from blocker to receiver.
// The shader is written out for its lamps, one call per lamp with its shadow map named by a
// constant, and the shadow lookups only for the lamps that have a map: llvmpipe runs both
// sides of a branch, a loop over the lamps and a sampler array indexed by a variable make
// every pixel several times dearer, even with no lamp at all.
namespace {

// Version 4.00 for textureGather.
constexpr const char* kPhysicalShaderDeclarations = R"(#version 400 core
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
uniform vec3 lamp_direction[4];
uniform float lamp_strength[4];
uniform mat4 lamp_map_T_camera[4];
uniform float lamp_texel[4];          // a texel, in map units
uniform float lamp_spread[4];         // penumbra radius (map units) per unit of map depth
uniform float lamp_normal_offset[4];  // metres
uniform sampler2D lamp_shadow[4];               // depths
uniform sampler2DShadow lamp_shadow_compare[4];  // depths compared, bilinearly filtered
layout(location = 3) out vec4 out_color;

const float PI = 3.14159265358979;

vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

float ggx(float nh, float a2) {
  float d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}
float smith(float nx, float a2) { return 2.0 * nx / (nx + sqrt(a2 + (1.0 - a2) * nx * nx)); }

// The fraction of lamp i's disc seen from p (normal n): 1 unshadowed, 0 in the umbra. A
// map is cleared to 1, beyond every caster, while receivers may lie further still: only
// depths below min(1, receiver depth) block.
float lit_fraction(int i, sampler2D map, sampler2DShadow compared_map, vec3 p, vec3 n) {
  vec3 m = (lamp_map_T_camera[i] * vec4(p + lamp_normal_offset[i] * n, 1.0)).xyz;
  float depth = m.z - 2.0 * lamp_texel[i];
  // Blockers: the 16 texels of 4 gathers spread over the widest penumbra at this depth.
  float search = max(lamp_spread[i] * m.z, lamp_texel[i]);
  vec4 blockers = vec4(0.0), blocker_depths = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    vec2 offset = vec2((k & 1) == 0 ? -0.5 : 0.5, k < 2 ? -0.5 : 0.5) * search;
    vec4 d = textureGather(map, m.xy + offset);
    vec4 blocking = vec4(lessThan(d, vec4(min(depth, 1.0))));
    blockers += blocking;
    blocker_depths += blocking * d;
  }
  float count = dot(blockers, vec4(1.0));
  float blocker_depth = dot(blocker_depths, vec4(1.0)) / max(count, 1.0);
  // Filtering: 4 bilinear comparisons (16 texels) over the penumbra the blockers project.
  float radius = max(lamp_spread[i] * (m.z - blocker_depth), lamp_texel[i]);
  float lit = 0.0;
  for (int k = 0; k < 4; ++k) {
    vec2 offset = vec2((k & 1) == 0 ? -0.5 : 0.5, k < 2 ? -0.5 : 0.5) * radius;
    lit += texture(compared_map, vec3(m.xy + offset, min(depth, 1.0)));
  }
  bool outside = any(lessThan(m.xy, vec2(0.0))) || any(greaterThan(m.xy, vec2(1.0)));
  return outside || count == 0.0 ? 1.0 : 0.25 * lit;
}

// Lamp i's light reflected towards the camera, unshadowed.
vec3 lamp_light(int i, vec3 n, vec3 v, float nv, float a2, vec3 f0, vec3 diffuse_color) {
  vec3 l = -lamp_direction[i];
  float nl = max(dot(n, l), 0.0);
  vec3 h = normalize(l + v);
  float vh = max(dot(v, h), 0.0);
  float m = 1.0 - vh, m2 = m * m;
  vec3 fresnel = f0 + (1.0 - f0) * (m2 * m2 * m);
  vec3 specular_brdf =
      ggx(max(dot(n, h), 0.0), a2) * smith(nl, a2) * smith(nv, a2) * fresnel / max(4.0 * nl * nv, 1e-6);
  return (diffuse_color + PI * specular_brdf) * lamp_strength[i] * nl;
}

void main() {
  // Texture rows are uploaded top row first, texture coordinates have v up.
  vec3 base = has_texture ? texture(diffuse_texture, vec2(f_texcoord.x, 1.0 - f_texcoord.y)).rgb : diffuse_rgb;
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
)";

}  // namespace

std::string physical_fragment_shader(int lamp_count, unsigned shadow_mask) {
  if (lamp_count < 0 || lamp_count > kMaxLamps)
    throw std::invalid_argument("physical shader: lamp count " + std::to_string(lamp_count) + " outside 0.." +
                                std::to_string(kMaxLamps));
  std::string source = kPhysicalShaderDeclarations;
  for (int i = 0; i < lamp_count; ++i) {
    const std::string lamp = std::to_string(i);
    source += "  color += lamp_light(" + lamp + ", n, v, nv, a2, f0, diffuse_color)";
    if (shadow_mask & (1u << i))
      source += " * lit_fraction(" + lamp + ", lamp_shadow[" + lamp + "], lamp_shadow_compare[" + lamp +
                "], f_camera_position, n)";
    source += ";\n";
  }
  source += "  out_color = vec4(linear_to_srgb(color), 1.0);\n}\n";
  return source;
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
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenSamplers(1, &depth_sampler_);
  glGenSamplers(1, &compare_sampler_);
  for (GLuint sampler : {depth_sampler_, compare_sampler_}) {
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glSamplerParameteri(depth_sampler_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(depth_sampler_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(depth_sampler_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  glSamplerParameteri(compare_sampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(compare_sampler_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(compare_sampler_, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glSamplerParameteri(compare_sampler_, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);  // lit: receiver at or before the map
}

ShadowMaps::~ShadowMaps() {
  glDeleteSamplers(1, &depth_sampler_);
  glDeleteSamplers(1, &compare_sampler_);
  glDeleteTextures(kMaxLamps, textures_);
  glDeleteFramebuffers(1, &fbo_);
}

bool ShadowMaps::is_current(int lamp, const Eigen::Vector3d& direction_in_world,
                            const std::vector<ShadowCaster>& casters) const {
  const Fit& f = fits_[lamp];
  if (!f.drawn || f.casters.size() != casters.size()) return false;
  // A shadow moves by its distance from the caster (at most the map's depth range) times
  // the lamp's turn, and by a caster's own motion.
  const double tolerance = 0.5 * texel_metres(lamp);
  const double turn = std::acos(std::clamp(f.direction.dot(direction_in_world.normalized()), -1.0, 1.0));
  if (turn * depth_range_metres(lamp) > tolerance) return false;
  for (std::size_t i = 0; i < casters.size(); ++i) {
    const ShadowCaster &was = f.casters[i], &now = casters[i];
    if (was.body != now.body || was.radius != now.radius) return false;
    const Eigen::AngleAxisd rotation(was.world_T_body.rotation().transpose() * now.world_T_body.rotation());
    if ((was.world_T_body.translation() - now.world_T_body.translation()).norm() + rotation.angle() * now.radius >
        tolerance)
      return false;
  }
  return true;
}

bool ShadowMaps::fit(int lamp, const Eigen::Vector3d& direction_in_world, const std::vector<ShadowCaster>& casters) {
  Fit& f = fits_[lamp];
  f.drawn = false;
  if (casters.empty()) return false;
  const Eigen::Vector3d w = direction_in_world.normalized();
  const Eigen::Vector3d u = w.unitOrthogonal();
  f.light_R_world.row(0) = u.transpose();
  f.light_R_world.row(1) = w.cross(u).transpose();
  f.light_R_world.row(2) = w.transpose();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const ShadowCaster& c : casters) {
    const Eigen::Vector3d p = f.light_R_world * c.centre;
    lo = lo.cwiseMin((p.array() - c.radius).matrix());
    hi = hi.cwiseMax((p.array() + c.radius).matrix());
  }
  f.centre = 0.5 * (lo + hi).head<2>();
  f.half_extent = 0.5 * (hi - lo).head<2>().maxCoeff() * 1.01;
  const double margin = 0.01 * (hi.z() - lo.z());
  f.near = lo.z() - margin;
  f.far = hi.z() + margin;
  f.direction = w;
  f.casters = casters;
  return true;
}

Eigen::Matrix4d ShadowMaps::map_T_world(int lamp) const {
  const Fit& f = fits_[lamp];
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  const double to_map = 0.5 / f.half_extent, depth = 1.0 / (f.far - f.near);
  m.block<2, 3>(0, 0) = to_map * f.light_R_world.topRows<2>();
  m.block<2, 1>(0, 3) = Eigen::Vector2d::Constant(0.5) - to_map * f.centre;
  m.block<1, 3>(2, 0) = depth * f.light_R_world.row(2);
  m(2, 3) = -depth * f.near;
  return m;
}

Eigen::Matrix4f ShadowMaps::clip_T_world(int lamp, bool zero_to_one_clip) const {
  Eigen::Matrix4d clip_T_map = Eigen::Matrix4d::Identity();
  clip_T_map.block<2, 2>(0, 0) *= 2.0;
  clip_T_map.block<2, 1>(0, 3).setConstant(-1.0);
  if (!zero_to_one_clip) clip_T_map(2, 2) = 2.0, clip_T_map(2, 3) = -1.0;
  return (clip_T_map * map_T_world(lamp)).cast<float>();
}

void ShadowMaps::begin_drawing(int lamp) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, textures_[lamp], 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RenderError("shadow map framebuffer of " + std::to_string(size_) + "x" + std::to_string(size_) +
                      " is incomplete");
  fits_[lamp].drawn = true;
  glViewport(0, 0, size_, size_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDepthFunc(GL_LESS);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
}

void ShadowMaps::bind_for_lookup(int lamp, int depth_unit, int compare_unit) const {
  for (const auto& [unit, sampler] :
       {std::pair{depth_unit, depth_sampler_}, std::pair{compare_unit, compare_sampler_}}) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, textures_[lamp]);
    glBindSampler(unit, sampler);
  }
}

}  // namespace icgp
