// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/renderer.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <array>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

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

GLuint link_program() {
  const GLuint shaders[] = {compile_shader(GL_VERTEX_SHADER, kVertexShader),
                            compile_shader(GL_GEOMETRY_SHADER, kGeometryShader),
                            compile_shader(GL_FRAGMENT_SHADER, kFragmentShader)};
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

/// Offscreen render targets of one image size.
struct Framebuffer {
  GLuint fbo = 0;
  std::array<GLuint, kAttachmentCount> color{};
  GLuint depth_buffer = 0;

  Framebuffer(int width, int height) {
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    const GLenum formats[kAttachmentCount] = {GL_R32F, GL_RGBA32F, GL_R8UI, GL_RGBA8};
    glGenRenderbuffers(kAttachmentCount, color.data());
    for (int i = 0; i < kAttachmentCount; ++i) {
      glBindRenderbuffer(GL_RENDERBUFFER, color[i]);
      glRenderbufferStorage(GL_RENDERBUFFER, formats[i], width, height);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_RENDERBUFFER, color[i]);
    }
    glGenRenderbuffers(1, &depth_buffer);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RenderError("offscreen framebuffer of " + std::to_string(width) + "x" + std::to_string(height) +
                        " is incomplete");
  }
  ~Framebuffer() {
    glDeleteRenderbuffers(kAttachmentCount, color.data());
    glDeleteRenderbuffers(1, &depth_buffer);
    glDeleteFramebuffers(1, &fbo);
  }
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;
};

struct GpuPart {
  GLuint vao = 0, vertex_buffer = 0, texcoord_buffer = 0, index_buffer = 0, texture = 0;
  GLsizei index_count = 0;
  Eigen::Vector3f diffuse_rgb;
};

struct GpuBody {
  std::vector<GpuPart> parts;
  std::uint8_t id = 0;
  Pose world_T_body;
  bool visible = true;
  Eigen::Vector3d centre;  ///< of the bounding sphere, body frame
  double radius = 0.0;
};

GLuint upload_texture(const cv::Mat& bgr) {
  const cv::Mat image = bgr.isContinuous() ? bgr : bgr.clone();
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.cols, image.rows, 0, GL_BGR, GL_UNSIGNED_BYTE, image.data);
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

GpuPart upload_part(const MeshPart& part) {
  GpuPart gpu;
  gpu.diffuse_rgb = part.material.diffuse_rgb;
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
  bool reversed_z = false;  ///< glClipControl available: float depth with uniform precision
  std::map<std::pair<int, int>, std::unique_ptr<Framebuffer>> framebuffers;
  std::vector<GpuBody> bodies;
  Lighting lighting;
  struct {
    GLint camera_T_body, projection, body_id, has_texture, diffuse_texture, diffuse_rgb, light_direction, ambient,
        diffuse;
  } uniforms{};

  Impl() {
    program = link_program();
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    reversed_z = major > 4 || (major == 4 && minor >= 5);
    uniforms = {glGetUniformLocation(program, "camera_T_body"), glGetUniformLocation(program, "projection"),
                glGetUniformLocation(program, "body_id"),       glGetUniformLocation(program, "has_texture"),
                glGetUniformLocation(program, "diffuse_texture"), glGetUniformLocation(program, "diffuse_rgb"),
                glGetUniformLocation(program, "light_direction"), glGetUniformLocation(program, "ambient"),
                glGetUniformLocation(program, "diffuse")};
  }

  ~Impl() {
    context.make_current();
    for (auto& body : bodies)
      for (auto& part : body.parts) release_part(part);
    framebuffers.clear();
    glDeleteProgram(program);
  }

  Framebuffer& framebuffer(int width, int height) {
    auto& fb = framebuffers[{width, height}];
    if (!fb) fb = std::make_unique<Framebuffer>(width, height);
    return *fb;
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
  for (const auto& part : mesh.parts) {
    for (const auto& v : part.vertices) body.radius = std::max(body.radius, (v.cast<double>() - body.centre).norm());
    body.parts.push_back(upload_part(part));
  }
  impl_->bodies.push_back(std::move(body));
  return static_cast<BodyHandle>(impl_->bodies.size() - 1);
}

void Renderer::set_body_pose(BodyHandle body, const Pose& world_T_body) { impl_->body(body).world_T_body = world_T_body; }
const Pose& Renderer::body_pose(BodyHandle body) const { return impl_->body(body).world_T_body; }
void Renderer::set_body_visible(BodyHandle body, bool visible) { impl_->body(body).visible = visible; }
void Renderer::set_lighting(const Lighting& lighting) { impl_->lighting = lighting; }

RenderOutput Renderer::render(const Intrinsics& intrinsics, const Pose& camera_T_world, unsigned targets) {
  intrinsics.validate("render intrinsics");
  const int W = intrinsics.width, H = intrinsics.height;
  RenderOutput out;
  if (targets & kRenderDepth) out.depth = cv::Mat::zeros(H, W, CV_32FC1);
  if (targets & kRenderNormals) out.normals = cv::Mat::zeros(H, W, CV_32FC3);
  if (targets & kRenderIds) out.ids = cv::Mat::zeros(H, W, CV_8UC1);
  if (targets & kRenderColor) {
    const Eigen::Vector3f bg = 255.f * impl_->lighting.background_rgb;
    out.color = cv::Mat(H, W, CV_8UC3, cv::Scalar(bg.z(), bg.y(), bg.x()));
  }
  double near = 0.0, far = 0.0;
  if (!impl_->depth_range(camera_T_world, near, far)) return out;  // nothing in front of the camera

  impl_->context.make_current();
  Framebuffer& fb = impl_->framebuffer(W, H);
  glBindFramebuffer(GL_FRAMEBUFFER, fb.fbo);
  glViewport(0, 0, W, H);
  GLenum draw_buffers[kAttachmentCount];
  for (int i = 0; i < kAttachmentCount; ++i)
    draw_buffers[i] = (targets & (1u << i)) ? GL_COLOR_ATTACHMENT0 + i : GL_NONE;
  glDrawBuffers(kAttachmentCount, draw_buffers);

  const float zeros[4] = {0.f, 0.f, 0.f, 0.f};
  const GLuint zero_id[4] = {0, 0, 0, 0};
  const Eigen::Vector4f background(impl_->lighting.background_rgb.x(), impl_->lighting.background_rgb.y(),
                                   impl_->lighting.background_rgb.z(), 1.f);
  if (targets & kRenderDepth) glClearBufferfv(GL_COLOR, kDepthAttachment, zeros);
  if (targets & kRenderNormals) glClearBufferfv(GL_COLOR, kNormalAttachment, zeros);
  if (targets & kRenderIds) glClearBufferuiv(GL_COLOR, kIdAttachment, zero_id);
  if (targets & kRenderColor) glClearBufferfv(GL_COLOR, kColorAttachment, background.data());

  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  if (impl_->reversed_z) {
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glDepthFunc(GL_GREATER);
    glClearDepth(0.0);
  } else {
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
  }
  glClear(GL_DEPTH_BUFFER_BIT);
  impl_->draw(intrinsics, camera_T_world, near, far);

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

std::string Renderer::description() const {
  impl_->context.make_current();
  return impl_->context.description();
}

}  // namespace icgp
