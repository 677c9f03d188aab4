// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/renderer.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>

#include "framebuffer.h"
#include "physical_shading.h"
#include "icgp/render/egl_context.h"

namespace icgp {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 body_position;
layout(location = 1) in vec2 texcoord;
uniform mat4 camera_T_body;
uniform mat4 projection;
out vec3 g_camera_position;
out vec2 g_texcoord;
void main() {
  vec4 p = camera_T_body * vec4(body_position, 1.0);
  g_camera_position = p.xyz;
  g_texcoord = texcoord;
  gl_Position = projection * p;
}
)";

// The face normal comes from the triangle itself, so normals are exact for the mesh and
// need no per-vertex normals (which would be smoothed across the edges of a box).
constexpr const char* kGeometryShader = R"(#version 330 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec3 g_camera_position[];
in vec2 g_texcoord[];
out vec3 f_camera_position;
out vec2 f_texcoord;
flat out vec3 f_normal;
void main() {
  vec3 n = normalize(cross(g_camera_position[1] - g_camera_position[0],
                           g_camera_position[2] - g_camera_position[0]));
  if (dot(n, g_camera_position[0]) > 0.0) n = -n;  // the seen side faces the camera
  for (int i = 0; i < 3; ++i) {
    gl_Position = gl_in[i].gl_Position;
    f_camera_position = g_camera_position[i];
    f_texcoord = g_texcoord[i];
    f_normal = n;
    EmitVertex();
  }
  EndPrimitive();
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 f_camera_position;
in vec2 f_texcoord;
flat in vec3 f_normal;
uniform uint body_id;
uniform bool has_texture;
uniform sampler2D diffuse_texture;
uniform vec3 diffuse_rgb;
uniform vec3 light_direction;
uniform float ambient;
uniform float diffuse;
layout(location = 0) out float out_depth;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out uint out_id;
layout(location = 3) out vec4 out_color;
void main() {
  out_depth = f_camera_position.z;
  out_normal = vec4(f_normal, 0.0);
  out_id = body_id;
  // Texture rows are uploaded top row first, texture coordinates have v up.
  vec3 albedo = has_texture ? texture(diffuse_texture, vec2(f_texcoord.x, 1.0 - f_texcoord.y)).rgb : diffuse_rgb;
  float shade = ambient + diffuse * max(dot(f_normal, -light_direction), 0.0);
  out_color = vec4(clamp(albedo * shade, 0.0, 1.0), 1.0);
}
)";

// Silhouette renders for model generation: ids only, depth comes from the depth buffer.
// Without shading, colour outputs or a geometry shader this is several times cheaper per
// pixel on llvmpipe, which matters for thousands of 2000x2000 views.
constexpr const char* kSilhouetteVertexShader = R"(#version 330 core
layout(location = 0) in vec3 body_position;
uniform mat4 projection_T_body;
void main() { gl_Position = projection_T_body * vec4(body_position, 1.0); }
)";

constexpr const char* kSilhouetteFragmentShader = R"(#version 330 core
uniform uint body_id;
layout(location = 0) out uint out_id;
void main() { out_id = body_id; }
)";

/// Which lamps have a shadow map in this render: bit i for lamp i.
using LampShadows = unsigned;

/// Texels per side of a lamp's shadow map: 0.2 mm on the 0.2 m box and its props.
constexpr int kShadowMapSize = 1024;

enum Attachment { kDepthAttachment = 0, kNormalAttachment, kIdAttachment, kColorAttachment, kAttachmentCount };

GLuint compile_shader(GLenum type, const char* source) {
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::array<char, 2048> log{};
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteShader(shader);
    throw RenderError(std::string("renderer shader does not compile: ") + log.data());
  }
  return shader;
}

GLuint link_program(const std::vector<GLuint>& shaders) {
  GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    std::array<char, 2048> log{};
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteProgram(program);
    throw RenderError(std::string("renderer shaders do not link: ") + log.data());
  }
  return program;
}

struct GpuPart {
  GLuint vao = 0, vertex_buffer = 0, texcoord_buffer = 0, index_buffer = 0, texture = 0;
  /// The texture's copy as sRGB, which the sampler decodes to linear light for physical
  /// renders; made with the first one. The texture itself stays raw for the Lambertian
  /// shader (the tracker's renders), mipmaps included.
  GLuint srgb_texture = 0;
  GLsizei index_count = 0;
  Eigen::Vector3f diffuse_rgb;
  float roughness = 0.5f, metallic = 0.f, specular = 0.5f;
};

struct GpuBody {
  std::vector<GpuPart> parts;
  std::uint8_t id = 0;
  Pose world_T_body;
  bool visible = true;
  bool casts_shadows = true;
  Eigen::Vector3d centre;  ///< of the bounding sphere, body frame
  double radius = 0.0;
  Eigen::Vector3d box_min, box_max;  ///< axis-aligned bounding box, body frame
};

/// Zeroes the part of `old` that `now` does not cover in both images.
void zero_uncovered(const cv::Rect& old, const cv::Rect& now, SilhouetteImages& images) {
  const cv::Rect keep = old & now;
  std::vector<cv::Rect> bands;
  if (keep.empty()) {
    bands.push_back(old);
  } else {
    bands = {{old.x, old.y, old.width, keep.y - old.y},
             {old.x, keep.br().y, old.width, old.br().y - keep.br().y},
             {old.x, keep.y, keep.x - old.x, keep.height},
             {keep.br().x, keep.y, old.br().x - keep.br().x, keep.height}};
  }
  for (const cv::Rect& band : bands)
    if (!band.empty()) {
      images.ids(band).setTo(0);
      images.inverse_depth(band).setTo(0);
    }
}

/// The bound texture's mipmaps, sampled trilinearly and repeating, as a surface's texture is.
void mipmap_for_tiling() {
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
}

GLuint upload_texture(const cv::Mat& bgr) {
  const cv::Mat image = bgr.isContinuous() ? bgr : bgr.clone();
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.cols, image.rows, 0, GL_BGR, GL_UNSIGNED_BYTE, image.data);
  mipmap_for_tiling();
  return texture;
}

GpuPart upload_part(const MeshPart& part) {
  GpuPart gpu;
  gpu.diffuse_rgb = part.material.diffuse_rgb;
  gpu.roughness = part.material.roughness;
  gpu.metallic = part.material.metallic;
  gpu.specular = part.material.specular;
  gpu.index_count = static_cast<GLsizei>(3 * part.triangles.size());
  glGenVertexArrays(1, &gpu.vao);
  glBindVertexArray(gpu.vao);

  glGenBuffers(1, &gpu.vertex_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, gpu.vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, part.vertices.size() * sizeof(Eigen::Vector3f), part.vertices.data(),
               GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector3f), nullptr);
  glEnableVertexAttribArray(0);

  const bool textured = !part.material.texture_bgr.empty() && part.texcoords.size() == part.vertices.size();
  if (textured) {
    glGenBuffers(1, &gpu.texcoord_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, gpu.texcoord_buffer);
    glBufferData(GL_ARRAY_BUFFER, part.texcoords.size() * sizeof(Eigen::Vector2f), part.texcoords.data(),
                 GL_STATIC_DRAW);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector2f), nullptr);
    glEnableVertexAttribArray(1);
    gpu.texture = upload_texture(part.material.texture_bgr);
  } else {
    glVertexAttrib2f(1, 0.f, 0.f);
  }

  glGenBuffers(1, &gpu.index_buffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.index_buffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, part.triangles.size() * sizeof(Eigen::Vector3i), part.triangles.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  return gpu;
}

void release_part(GpuPart& part) {
  glDeleteVertexArrays(1, &part.vao);
  const GLuint buffers[] = {part.vertex_buffer, part.texcoord_buffer, part.index_buffer};
  glDeleteBuffers(3, buffers);
  if (part.texture) glDeleteTextures(1, &part.texture);
  if (part.srgb_texture) glDeleteTextures(1, &part.srgb_texture);
}

/// The texture's base level copied into an sRGB texture (same bytes, read as sRGB-encoded),
/// with mipmaps averaged in linear light as a camera's pixels average it.
GLuint srgb_copy(GLuint texture) {
  GLint width = 0, height = 0;
  glBindTexture(GL_TEXTURE_2D, texture);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
  GLuint copy = 0;
  glGenTextures(1, &copy);
  glBindTexture(GL_TEXTURE_2D, copy);
  const int levels = 1 + static_cast<int>(std::floor(std::log2(std::max(width, height))));
  glTexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8, width, height);
  glCopyImageSubData(texture, GL_TEXTURE_2D, 0, 0, 0, 0, copy, GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
  mipmap_for_tiling();
  return copy;
}

void validate_mesh(const Mesh& mesh) {
  for (const auto& part : mesh.parts)
    for (const auto& t : part.triangles)
      if ((t.array() < 0).any() || (t.array() >= static_cast<int>(part.vertices.size())).any())
        throw std::invalid_argument("mesh '" + mesh.source + "' has a triangle index outside its " +
                                    std::to_string(part.vertices.size()) + " vertices");
}

}  // namespace

struct Renderer::Impl {
  EglContext context;
  GLuint program = 0;
  GLuint silhouette_program = 0;
  bool reversed_z = false;  ///< glClipControl available: float depth with uniform precision
  std::map<std::pair<int, int>, std::unique_ptr<Framebuffer>> framebuffers;
  std::map<std::pair<int, int>, std::unique_ptr<Framebuffer>> silhouette_framebuffers;
  /// Antialiased or physical colour: drawn into a multisampled target (by width, height and
  /// samples, which a caller may switch from frame to frame), resolved into a plain one.
  std::map<std::tuple<int, int, int>, std::unique_ptr<Framebuffer>> multisample_framebuffers;
  std::map<std::pair<int, int>, std::unique_ptr<Framebuffer>> resolve_framebuffers;
  int color_samples = 0;
  std::vector<GpuBody> bodies;
  Lighting lighting;
  /// Colour renders are physically based while this is set; the shadow maps are made with
  /// the first such lighting (a tracker's renderer never needs them).
  std::optional<PhysicalLighting> physical;
  std::unique_ptr<ShadowMaps> shadow_maps;
  struct {
    GLint camera_T_body, projection, body_id, has_texture, diffuse_texture, diffuse_rgb, light_direction, ambient,
        diffuse;
  } uniforms{};
  struct {
    GLint projection_T_body, body_id;
  } silhouette_uniforms{};
  /// The physical shader compiled for each lamp count and set of shadowed lamps, made when
  /// first used.
  struct PhysicalProgram {
    GLuint id = 0;
    GLint camera_T_body, projection, has_texture, diffuse_texture, diffuse_rgb, roughness, metallic, specular, ambient,
        lamp_direction, lamp_strength, lamp_map_T_camera, lamp_texel, lamp_spread, lamp_normal_offset, lamp_shadow,
        lamp_shadow_compare;
  };
  std::map<std::pair<int, LampShadows>, PhysicalProgram> physical_programs;

  Impl() {
    program = link_program({compile_shader(GL_VERTEX_SHADER, kVertexShader),
                            compile_shader(GL_GEOMETRY_SHADER, kGeometryShader),
                            compile_shader(GL_FRAGMENT_SHADER, kFragmentShader)});
    silhouette_program = link_program({compile_shader(GL_VERTEX_SHADER, kSilhouetteVertexShader),
                                       compile_shader(GL_FRAGMENT_SHADER, kSilhouetteFragmentShader)});
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    reversed_z = major > 4 || (major == 4 && minor >= 5);
    uniforms = {glGetUniformLocation(program, "camera_T_body"), glGetUniformLocation(program, "projection"),
                glGetUniformLocation(program, "body_id"),       glGetUniformLocation(program, "has_texture"),
                glGetUniformLocation(program, "diffuse_texture"), glGetUniformLocation(program, "diffuse_rgb"),
                glGetUniformLocation(program, "light_direction"), glGetUniformLocation(program, "ambient"),
                glGetUniformLocation(program, "diffuse")};
    silhouette_uniforms = {glGetUniformLocation(silhouette_program, "projection_T_body"),
                           glGetUniformLocation(silhouette_program, "body_id")};
  }

  ~Impl() {
    context.make_current();
    for (auto& body : bodies)
      for (auto& part : body.parts) release_part(part);
    framebuffers.clear();
    silhouette_framebuffers.clear();
    multisample_framebuffers.clear();
    resolve_framebuffers.clear();
    shadow_maps.reset();
    glDeleteProgram(program);
    glDeleteProgram(silhouette_program);
    for (const auto& [key, p] : physical_programs) glDeleteProgram(p.id);
  }

  const PhysicalProgram& physical_program(int lamp_count, LampShadows shadows) {
    PhysicalProgram& p = physical_programs[{lamp_count, shadows}];
    if (p.id) return p;
    const std::string fragment_shader = physical_fragment_shader(lamp_count, shadows);
    p.id = link_program({compile_shader(GL_VERTEX_SHADER, kVertexShader),
                         compile_shader(GL_GEOMETRY_SHADER, kGeometryShader),
                         compile_shader(GL_FRAGMENT_SHADER, fragment_shader.c_str())});
    const auto at = [&](const char* name) { return glGetUniformLocation(p.id, name); };
    p.camera_T_body = at("camera_T_body"), p.projection = at("projection"), p.has_texture = at("has_texture");
    p.diffuse_texture = at("diffuse_texture"), p.diffuse_rgb = at("diffuse_rgb"), p.roughness = at("roughness");
    p.metallic = at("metallic"), p.specular = at("specular"), p.ambient = at("ambient");
    p.lamp_direction = at("lamp_direction"), p.lamp_strength = at("lamp_strength");
    p.lamp_map_T_camera = at("lamp_map_T_camera");
    p.lamp_texel = at("lamp_texel"), p.lamp_spread = at("lamp_spread"), p.lamp_normal_offset = at("lamp_normal_offset");
    p.lamp_shadow = at("lamp_shadow"), p.lamp_shadow_compare = at("lamp_shadow_compare");
    return p;
  }

  Eigen::Vector3f background_rgb() const { return physical ? physical->background_rgb : lighting.background_rgb; }

  /// A framebuffer of at least width x height, sides rounded up to kFramebufferGranule: the
  /// focused renders' sizes change from frame to frame with the body's distance, and one
  /// framebuffer per size would be allocated anew on most frames and all kept. Renders use
  /// its bottom-left width x height (viewport, scissor and reads).
  Framebuffer& framebuffer(int width, int height) {
    const auto round_up = [](int side) {
      return (side + kFramebufferGranule - 1) / kFramebufferGranule * kFramebufferGranule;
    };
    const int W = round_up(width), H = round_up(height);
    auto& fb = framebuffers[{W, H}];
    if (!fb) fb = std::make_unique<Framebuffer>(W, H, std::vector<GLenum>{GL_R32F, GL_RGBA32F, GL_R8UI, GL_RGBA8});
    return *fb;
  }

  /// Draws the shaded colour (physically based when `physical` is set, after the lamps'
  /// shadow maps) with `color_samples` samples per pixel and resolves it into
  /// `color` (CV_8UC3, the image size): edges become coverage-weighted blends as a camera's
  /// pixel integrates them. Depth, normals and ids stay single-sampled: a blend of two ids
  /// or depths would be neither surface.
  void render_multisampled_color(const Intrinsics& k, const Pose& camera_T_world, double near, double far,
                                 const Eigen::Vector4f& background, cv::Mat& color) {
    const int W = k.width, H = k.height;
    auto& multisampled = multisample_framebuffers[{W, H, color_samples}];
    if (!multisampled) multisampled = std::make_unique<Framebuffer>(W, H, std::vector<GLenum>{GL_RGBA8}, color_samples);
    auto& resolved = resolve_framebuffers[{W, H}];
    if (!resolved) resolved = std::make_unique<Framebuffer>(W, H, std::vector<GLenum>{GL_RGBA8});
    const LampShadows shadows = physical ? draw_shadow_maps(camera_T_world) : 0u;

    glBindFramebuffer(GL_FRAMEBUFFER, multisampled->fbo);
    glViewport(0, 0, W, H);
    // The shader writes colour at location kColorAttachment: route only that one.
    GLenum draw_buffers[kAttachmentCount] = {GL_NONE, GL_NONE, GL_NONE, GL_NONE};
    draw_buffers[kColorAttachment] = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(kAttachmentCount, draw_buffers);
    glClearBufferfv(GL_COLOR, kColorAttachment, background.data());
    clear_depth_for_drawing();
    if (physical) {
      draw_physical(k, camera_T_world, near, far, shadows);
    } else {
      draw(k, camera_T_world, near, far);
    }

    glBindFramebuffer(GL_READ_FRAMEBUFFER, multisampled->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved->fbo);
    const GLenum resolve_buffer = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &resolve_buffer);
    glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolved->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, W, H, GL_BGR, GL_UNSIGNED_BYTE, color.data);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  Framebuffer& silhouette_framebuffer(int width, int height) {
    auto& fb = silhouette_framebuffers[{width, height}];
    if (!fb) fb = std::make_unique<Framebuffer>(width, height, std::vector<GLenum>{GL_R8UI});
    return *fb;
  }

  /// Depth test towards the camera and a cleared depth buffer, for the bound framebuffer.
  void clear_depth_for_drawing() const {
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (reversed_z) {
      glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
      glDepthFunc(GL_GREATER);
      glClearDepth(0.0);
    } else {
      glDepthFunc(GL_LESS);
      glClearDepth(1.0);
    }
    glClear(GL_DEPTH_BUFFER_BIT);
  }

  GpuBody& body(BodyHandle handle) {
    if (handle < 0 || handle >= static_cast<int>(bodies.size()))
      throw std::out_of_range("renderer has no body " + std::to_string(handle));
    return bodies[handle];
  }

  /// Nearest and farthest Z of the visible bodies' bounding spheres; false when nothing
  /// visible is in front of the camera.
  bool depth_range(const Pose& camera_T_world, double& near, double& far) const {
    near = std::numeric_limits<double>::max();
    far = 0.0;
    for (const auto& b : bodies) {
      if (!b.visible) continue;
      const double z = (camera_T_world * b.world_T_body * b.centre).z();
      near = std::min(near, z - b.radius);
      far = std::max(far, z + b.radius);
    }
    if (far <= 0.0) return false;
    // A camera inside a bounding sphere still needs a positive near plane; 1e-4 of the
    // range keeps float depth precise while clipping only what is that close.
    near = std::max(near, far * 1e-4);
    far *= 1.001;
    return true;
  }

  Eigen::Matrix4f projection(const Intrinsics& k, double near, double far) const {
    // Maps the pixel-centre convention exactly: NDC x = (2u + 1)/W - 1, NDC y likewise
    // with image row 0 at window row 0, so glReadPixels returns rows top first.
    const double W = k.width, H = k.height;
    Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
    P(0, 0) = 2.0 * k.fu / W;
    P(0, 2) = (2.0 * k.pu + 1.0) / W - 1.0;
    P(1, 1) = 2.0 * k.fv / H;
    P(1, 2) = (2.0 * k.pv + 1.0) / H - 1.0;
    if (reversed_z) {  // depth = near / Z in [0, 1], larger is closer
      P(2, 3) = near;
    } else {
      P(2, 2) = (far + near) / (far - near);
      P(2, 3) = -2.0 * far * near / (far - near);
    }
    P(3, 2) = 1.0;
    return P.cast<float>();
  }

  void draw(const Intrinsics& k, const Pose& camera_T_world, double near, double far) {
    glUseProgram(program);
    const Eigen::Matrix4f P = projection(k, near, far);
    glUniformMatrix4fv(uniforms.projection, 1, GL_FALSE, P.data());
    glUniform3fv(uniforms.light_direction, 1, lighting.direction_in_camera.normalized().eval().data());
    glUniform1f(uniforms.ambient, lighting.ambient);
    glUniform1f(uniforms.diffuse, lighting.diffuse);
    glUniform1i(uniforms.diffuse_texture, 0);
    glActiveTexture(GL_TEXTURE0);
    for (const auto& b : bodies) {
      if (!b.visible) continue;
      const Eigen::Matrix4f camera_T_body = (camera_T_world * b.world_T_body).matrix().cast<float>();
      glUniformMatrix4fv(uniforms.camera_T_body, 1, GL_FALSE, camera_T_body.data());
      glUniform1ui(uniforms.body_id, b.id);
      for (const auto& part : b.parts) {
        glUniform1i(uniforms.has_texture, part.texture != 0);
        glUniform3fv(uniforms.diffuse_rgb, 1, part.diffuse_rgb.data());
        glBindTexture(GL_TEXTURE_2D, part.texture);
        glBindVertexArray(part.vao);
        glDrawElements(GL_TRIANGLES, part.index_count, GL_UNSIGNED_INT, nullptr);
      }
    }
    glBindVertexArray(0);
  }

  /// Each lit lamp's depth map of the shadow casters, for draw_physical; which lamps have one.
  LampShadows draw_shadow_maps(const Pose& camera_T_world) {
    LampShadows has_shadow = 0;
    std::vector<ShadowCaster> casters;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const GpuBody& b = bodies[i];
      if (b.visible && b.casts_shadows)
        casters.push_back({static_cast<int>(i), b.world_T_body, b.world_T_body * b.centre, b.radius});
    }
    const Eigen::Matrix3d world_R_camera = camera_T_world.rotation().transpose();
    const std::vector<Lamp>& lamps = physical->lamps;
    for (std::size_t i = 0; i < lamps.size(); ++i) {
      const int lamp = static_cast<int>(i);
      const Eigen::Vector3d direction = world_R_camera * lamps[i].direction_in_camera.cast<double>();
      if (!(lamps[i].strength > 0.f) || casters.empty()) continue;
      has_shadow |= 1u << i;
      if (shadow_maps->is_current(lamp, direction, casters)) continue;
      shadow_maps->fit(lamp, direction, casters);
      shadow_maps->begin_drawing(lamp);
      if (reversed_z) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
      draw_silhouette(shadow_maps->clip_T_world(lamp, reversed_z).cast<double>(), true);
    }
    return has_shadow;
  }

  void draw_physical(const Intrinsics& k, const Pose& camera_T_world, double near, double far,
                     LampShadows has_shadow) {
    const std::vector<Lamp>& lamps = physical->lamps;
    const auto count = static_cast<GLsizei>(lamps.size());
    const PhysicalProgram& u = physical_program(count, has_shadow);
    glUseProgram(u.id);
    const Eigen::Matrix4f P = projection(k, near, far);
    glUniformMatrix4fv(u.projection, 1, GL_FALSE, P.data());
    glUniform1f(u.ambient, physical->ambient);
    Eigen::Matrix<float, 3, kMaxLamps> directions = Eigen::Matrix<float, 3, kMaxLamps>::Zero();
    Eigen::Matrix<float, 16, kMaxLamps> map_T_camera = Eigen::Matrix<float, 16, kMaxLamps>::Zero();
    float strengths[kMaxLamps] = {}, texels[kMaxLamps] = {}, spreads[kMaxLamps] = {}, offsets[kMaxLamps] = {};
    GLint depth_units[kMaxLamps], compare_units[kMaxLamps];
    for (int i = 0; i < kMaxLamps; ++i) {
      depth_units[i] = 1 + i;  // unit 0: the parts' textures
      compare_units[i] = 1 + kMaxLamps + i;
      if (i >= count) continue;
      directions.col(i) = lamps[i].direction_in_camera.normalized();
      strengths[i] = lamps[i].strength;
      if (!(has_shadow & (1u << i))) continue;
      shadow_maps->bind_for_lookup(i, depth_units[i], compare_units[i]);
      const Eigen::Matrix4f m = (shadow_maps->map_T_world(i) * camera_T_world.inverse().matrix()).cast<float>();
      map_T_camera.col(i) = Eigen::Map<const Eigen::Matrix<float, 16, 1>>(m.data());
      const auto texel_metres = static_cast<float>(shadow_maps->texel_metres(i));
      texels[i] = 1.f / static_cast<float>(shadow_maps->size());
      // A penumbra's radius is the gap from blocker to receiver times tan(half the lamp's
      // angle); the shader measures the gap in map depth, the radius in map widths.
      const auto half_angle = static_cast<float>(deg_to_rad(0.5 * lamps[i].angle_deg));
      const auto depth_range = static_cast<float>(shadow_maps->depth_range_metres(i));
      spreads[i] = std::tan(half_angle) * depth_range * texels[i] / texel_metres;
      offsets[i] = 1.5f * texel_metres;  // off the surface by more than a texel's depth error
    }
    glUniform3fv(u.lamp_direction, count, directions.data());
    glUniform1fv(u.lamp_strength, count, strengths);
    glUniformMatrix4fv(u.lamp_map_T_camera, count, GL_FALSE, map_T_camera.data());
    glUniform1fv(u.lamp_texel, count, texels);
    glUniform1fv(u.lamp_spread, count, spreads);
    glUniform1fv(u.lamp_normal_offset, count, offsets);
    glUniform1iv(u.lamp_shadow, kMaxLamps, depth_units);
    glUniform1iv(u.lamp_shadow_compare, kMaxLamps, compare_units);
    glUniform1i(u.diffuse_texture, 0);
    glActiveTexture(GL_TEXTURE0);
    for (auto& b : bodies) {
      if (!b.visible) continue;
      const Eigen::Matrix4f camera_T_body = (camera_T_world * b.world_T_body).matrix().cast<float>();
      glUniformMatrix4fv(u.camera_T_body, 1, GL_FALSE, camera_T_body.data());
      for (auto& part : b.parts) {
        glUniform1i(u.has_texture, part.texture != 0);
        glUniform3fv(u.diffuse_rgb, 1, part.diffuse_rgb.data());
        glUniform1f(u.roughness, part.roughness);
        glUniform1f(u.metallic, part.metallic);
        glUniform1f(u.specular, part.specular);
        if (part.texture && !part.srgb_texture) part.srgb_texture = srgb_copy(part.texture);
        glBindTexture(GL_TEXTURE_2D, part.srgb_texture);
        glBindVertexArray(part.vao);
        glDrawElements(GL_TRIANGLES, part.index_count, GL_UNSIGNED_INT, nullptr);
      }
    }
    glBindVertexArray(0);
  }

  /// Ids and depth of the visible bodies (only those casting shadows when `casters_only`)
  /// projected by clip_T_world.
  void draw_silhouette(const Eigen::Matrix4d& clip_T_world, bool casters_only) {
    glUseProgram(silhouette_program);
    for (const auto& b : bodies) {
      if (!b.visible || (casters_only && !b.casts_shadows)) continue;
      const Eigen::Matrix4f projection_T_body = (clip_T_world * b.world_T_body.matrix()).cast<float>();
      glUniformMatrix4fv(silhouette_uniforms.projection_T_body, 1, GL_FALSE, projection_T_body.data());
      glUniform1ui(silhouette_uniforms.body_id, b.id);
      for (const auto& part : b.parts) {
        glBindVertexArray(part.vao);
        glDrawElements(GL_TRIANGLES, part.index_count, GL_UNSIGNED_INT, nullptr);
      }
    }
    glBindVertexArray(0);
  }

  /// The pixels the visible bodies can cover: the bounding rectangle of their projected
  /// bounding-box corners plus a pixel, clipped to the image; the whole image when a corner
  /// is not in front of the camera.
  cv::Rect footprint(const Intrinsics& k, const Pose& camera_T_world) const {
    const cv::Rect image(0, 0, k.width, k.height);
    double u_min = std::numeric_limits<double>::max(), v_min = u_min, u_max = -u_min, v_max = -u_min;
    for (const auto& b : bodies) {
      if (!b.visible) continue;
      const Pose camera_T_body = camera_T_world * b.world_T_body;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d corner((c & 1) ? b.box_max.x() : b.box_min.x(), (c & 2) ? b.box_max.y() : b.box_min.y(),
                                     (c & 4) ? b.box_max.z() : b.box_min.z());
        const Eigen::Vector3d X = camera_T_body * corner;
        if (!(X.z() > 0.0)) return image;
        const Eigen::Vector2d x = k.project<double>(X);
        u_min = std::min(u_min, x.x()), u_max = std::max(u_max, x.x());
        v_min = std::min(v_min, x.y()), v_max = std::max(v_max, x.y());
      }
    }
    if (u_min > u_max) return {};
    auto clamp = [](double x, int size) { return static_cast<int>(std::clamp(x, -1.0, static_cast<double>(size))); };
    const int x0 = clamp(std::floor(u_min) - 1, k.width), x1 = clamp(std::ceil(u_max) + 1, k.width);
    const int y0 = clamp(std::floor(v_min) - 1, k.height), y1 = clamp(std::ceil(v_max) + 1, k.height);
    return cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1) & image;
  }

  /// The id of the only visible body, or 0 when several bodies are visible.
  std::uint8_t single_visible_id() const {
    std::uint8_t id = 0;
    int visible = 0;
    for (const auto& b : bodies)
      if (b.visible) id = b.id, ++visible;
    return visible == 1 ? id : 0;
  }
};

ImageSquare square_around_sphere(const Intrinsics& k, const Eigen::Vector3d& centre, double radius, double margin) {
  if (!(centre.z() > radius))
    throw std::invalid_argument("square_around_sphere: the sphere must lie in front of the camera (Z " +
                                std::to_string(centre.z()) + " m, radius " + std::to_string(radius) + " m)");
  const Eigen::Vector2d c = k.project<double>(centre);
  // The projected sphere's extent is bounded by f·r / sqrt(Z² − r²) around the projected
  // centre (exact on the optical axis, conservative enough off it for a margin of 10 %).
  const double half = (1.0 + margin) * std::max(k.fu, k.fv) * radius / std::sqrt(centre.z() * centre.z() - radius * radius);
  return {c.x() + 0.5 - half, c.y() + 0.5 - half, 2.0 * half};
}

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

Renderer::BodyHandle Renderer::add_body(const Mesh& mesh, std::uint8_t id) {
  if (id == 0) throw std::invalid_argument("renderer body id 0 is reserved for the background");
  if (mesh.empty()) throw std::invalid_argument("mesh '" + mesh.source + "' has no triangles to render");
  validate_mesh(mesh);
  impl_->context.make_current();
  GpuBody body;
  body.id = id;
  Eigen::Vector3f lo, hi;
  mesh.bounds(lo, hi);
  body.centre = (0.5f * (lo + hi)).cast<double>();
  body.box_min = lo.cast<double>();
  body.box_max = hi.cast<double>();
  for (const auto& part : mesh.parts) {
    for (const auto& v : part.vertices) body.radius = std::max(body.radius, (v.cast<double>() - body.centre).norm());
    body.parts.push_back(upload_part(part));
  }
  impl_->bodies.push_back(std::move(body));
  return static_cast<BodyHandle>(impl_->bodies.size() - 1);
}

void Renderer::set_body_pose(BodyHandle body, const Pose& world_T_body) { impl_->body(body).world_T_body = world_T_body; }
void Renderer::set_body_visible(BodyHandle body, bool visible) { impl_->body(body).visible = visible; }
void Renderer::set_lighting(const Lighting& lighting) {
  impl_->lighting = lighting;
  impl_->physical.reset();
}

void Renderer::set_physical_lighting(const PhysicalLighting& lighting) {
  if (lighting.lamps.size() > static_cast<std::size_t>(kMaxLamps))
    throw std::invalid_argument("renderer: physically based lighting takes at most " + std::to_string(kMaxLamps) +
                                " lamps, got " + std::to_string(lighting.lamps.size()));
  for (const Lamp& lamp : lighting.lamps)
    if (!(lamp.direction_in_camera.norm() > 0.f) || !(lamp.strength >= 0.f) || !(lamp.angle_deg >= 0.f) ||
        !(lamp.angle_deg < 90.f))
      throw std::invalid_argument(
          "renderer: a lamp needs a non-zero direction, a strength >= 0 and an angle in [0, 90) degrees");
  impl_->context.make_current();
  if (!impl_->shadow_maps) impl_->shadow_maps = std::make_unique<ShadowMaps>(kShadowMapSize);
  impl_->physical = lighting;
}

void Renderer::set_body_casts_shadows(BodyHandle body, bool casts_shadows) {
  impl_->body(body).casts_shadows = casts_shadows;
}

void Renderer::set_color_antialiasing(int samples) {
  if (samples == impl_->color_samples) return;
  impl_->context.make_current();
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (samples < 0 || samples == 1 || samples > max_samples)
    throw std::invalid_argument("renderer: colour antialiasing samples must be 0 (off) or 2.." +
                                std::to_string(max_samples) + " on this OpenGL implementation, got " +
                                std::to_string(samples));
  impl_->color_samples = samples;
}

int Renderer::color_antialiasing() const { return impl_->color_samples; }

RenderOutput Renderer::render(const Intrinsics& intrinsics, const Pose& camera_T_world, unsigned targets) {
  intrinsics.validate("render intrinsics");
  const int W = intrinsics.width, H = intrinsics.height;
  RenderOutput out;
  if (targets & kRenderDepth) out.depth = cv::Mat::zeros(H, W, CV_32FC1);
  if (targets & kRenderNormals) out.normals = cv::Mat::zeros(H, W, CV_32FC3);
  if (targets & kRenderIds) out.ids = cv::Mat::zeros(H, W, CV_8UC1);
  if (targets & kRenderColor) {
    const Eigen::Vector3f bg = 255.f * impl_->background_rgb();
    out.color = cv::Mat(H, W, CV_8UC3, cv::Scalar(bg.z(), bg.y(), bg.x()));
  }
  double near = 0.0, far = 0.0;
  if (!impl_->depth_range(camera_T_world, near, far)) return out;  // nothing in front of the camera

  impl_->context.make_current();
  const Eigen::Vector4f background(impl_->background_rgb().x(), impl_->background_rgb().y(),
                                   impl_->background_rgb().z(), 1.f);
  if ((targets & kRenderColor) && (impl_->color_samples > 0 || impl_->physical)) {
    impl_->render_multisampled_color(intrinsics, camera_T_world, near, far, background, out.color);
    targets &= ~unsigned(kRenderColor);
    if (targets == 0) return out;
  }
  Framebuffer& fb = impl_->framebuffer(W, H);
  glBindFramebuffer(GL_FRAMEBUFFER, fb.fbo);
  glViewport(0, 0, W, H);
  glEnable(GL_SCISSOR_TEST);  // clears stay in the image's part of a larger framebuffer
  glScissor(0, 0, W, H);
  GLenum draw_buffers[kAttachmentCount];
  for (int i = 0; i < kAttachmentCount; ++i)
    draw_buffers[i] = (targets & (1u << i)) ? GL_COLOR_ATTACHMENT0 + i : GL_NONE;
  glDrawBuffers(kAttachmentCount, draw_buffers);

  const float zeros[4] = {0.f, 0.f, 0.f, 0.f};
  const GLuint zero_id[4] = {0, 0, 0, 0};
  if (targets & kRenderDepth) glClearBufferfv(GL_COLOR, kDepthAttachment, zeros);
  if (targets & kRenderNormals) glClearBufferfv(GL_COLOR, kNormalAttachment, zeros);
  if (targets & kRenderIds) glClearBufferuiv(GL_COLOR, kIdAttachment, zero_id);
  if (targets & kRenderColor) glClearBufferfv(GL_COLOR, kColorAttachment, background.data());
  impl_->clear_depth_for_drawing();
  impl_->draw(intrinsics, camera_T_world, near, far);
  glDisable(GL_SCISSOR_TEST);

  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  auto read = [&](Attachment a, GLenum format, GLenum type, cv::Mat& m) {
    glReadBuffer(GL_COLOR_ATTACHMENT0 + a);
    glReadPixels(0, 0, W, H, format, type, m.data);
  };
  if (targets & kRenderDepth) read(kDepthAttachment, GL_RED, GL_FLOAT, out.depth);
  if (targets & kRenderNormals) read(kNormalAttachment, GL_RGB, GL_FLOAT, out.normals);
  if (targets & kRenderIds) read(kIdAttachment, GL_RED_INTEGER, GL_UNSIGNED_BYTE, out.ids);
  if (targets & kRenderColor) read(kColorAttachment, GL_BGR, GL_UNSIGNED_BYTE, out.color);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return out;
}

RenderOutput Renderer::render_focused(const Intrinsics& intrinsics, const Pose& camera_T_world, double u_min,
                                      double v_min, double size, int out_size, unsigned targets,
                                      Intrinsics* crop_intrinsics) {
  if (!(size > 0.0) || out_size <= 0)
    throw std::invalid_argument("focused render needs a positive crop size and output size (got " +
                                std::to_string(size) + ", " + std::to_string(out_size) + ")");
  const Intrinsics crop = intrinsics.cropped(u_min, v_min, size, size, out_size, out_size);
  if (crop_intrinsics) *crop_intrinsics = crop;
  return render(crop, camera_T_world, targets);
}

void Renderer::render_silhouette(const Intrinsics& intrinsics, const Pose& camera_T_world, SilhouetteImages& out) {
  intrinsics.validate("silhouette render intrinsics");
  const int W = intrinsics.width, H = intrinsics.height;
  if (out.ids.size() != cv::Size(W, H) || out.ids.type() != CV_8UC1 || out.inverse_depth.size() != cv::Size(W, H) ||
      out.inverse_depth.type() != CV_32FC1) {
    out.ids = cv::Mat::zeros(H, W, CV_8UC1);
    out.inverse_depth = cv::Mat::zeros(H, W, CV_32FC1);
    out.footprint = cv::Rect();
  }
  double near = 0.0, far = 0.0;
  const cv::Rect footprint =
      impl_->depth_range(camera_T_world, near, far) ? impl_->footprint(intrinsics, camera_T_world) : cv::Rect();
  // Only the previous footprint can hold anything: clear what the new one does not redraw.
  zero_uncovered(out.footprint, footprint, out);
  out.footprint = footprint;
  out.depth_scale = near > 0.0 ? near : 1.0;
  if (footprint.empty()) return;  // nothing in front of the camera

  impl_->context.make_current();
  Framebuffer& fb = impl_->silhouette_framebuffer(W, H);
  glBindFramebuffer(GL_FRAMEBUFFER, fb.fbo);
  glViewport(0, 0, W, H);
  glEnable(GL_SCISSOR_TEST);  // clears and draws stay in the footprint
  glScissor(footprint.x, footprint.y, footprint.width, footprint.height);
  // One body's ids follow from where its depth was written: skip drawing them.
  const std::uint8_t single_id = impl_->single_visible_id();
  const GLenum draw_buffer = single_id ? GL_NONE : GL_COLOR_ATTACHMENT0;
  glDrawBuffers(1, &draw_buffer);
  if (!single_id) {
    const GLuint zero_id[4] = {0, 0, 0, 0};
    glClearBufferuiv(GL_COLOR, 0, zero_id);
  }
  impl_->clear_depth_for_drawing();
  impl_->draw_silhouette(impl_->projection(intrinsics, near, far).cast<double>() * camera_T_world.matrix(), false);
  glDisable(GL_SCISSOR_TEST);

  // Read the footprint straight into its place in the images.
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, W);
  cv::Mat inverse_depth = out.inverse_depth(footprint), ids = out.ids(footprint);
  glReadPixels(footprint.x, footprint.y, footprint.width, footprint.height, GL_DEPTH_COMPONENT, GL_FLOAT,
               inverse_depth.data);
  if (!single_id) {
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(footprint.x, footprint.y, footprint.width, footprint.height, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                 ids.data);
  }
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!impl_->reversed_z) {
    // Conventional depth d in [0, 1] is 1/Z mapped affinely: near/Z = ((f+n) - (2d-1)(f-n)) / 2f.
    for (int i = 0; i < inverse_depth.rows; ++i) {
      float* row = inverse_depth.ptr<float>(i);
      for (int j = 0; j < inverse_depth.cols; ++j)
        row[j] = row[j] < 1.f ? static_cast<float>(((far + near) - (2.0 * row[j] - 1.0) * (far - near)) / (2.0 * far))
                              : 0.f;
    }
  }
  if (single_id) {
    cv::compare(inverse_depth, 0.f, ids, cv::CMP_GT);  // 255 where drawn
    if (single_id != 255) ids &= single_id;             // 255 & id == id
  }
}

double Renderer::image_motion(const Intrinsics& k, const Pose& camera_T_world, const Pose& other_camera_T_world) const {
  double motion = 0.0;
  for (const auto& b : impl_->bodies) {
    if (!b.visible) continue;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1) ? b.box_max.x() : b.box_min.x(), (c & 2) ? b.box_max.y() : b.box_min.y(),
                                   (c & 4) ? b.box_max.z() : b.box_min.z());
      const Eigen::Vector3d world = b.world_T_body * corner;
      const Eigen::Vector3d X = camera_T_world * world, other = other_camera_T_world * world;
      if (!(X.z() > 0.0) || !(other.z() > 0.0)) continue;
      const Eigen::Vector2d x = k.project<double>(X);
      if (x.x() < -0.5 || x.y() < -0.5 || x.x() > k.width - 0.5 || x.y() > k.height - 0.5) continue;
      motion = std::max(motion, (k.project<double>(other) - x).norm());
    }
  }
  return motion;
}

std::string Renderer::description() const {
  impl_->context.make_current();
  return impl_->context.description();
}

}  // namespace icgp
