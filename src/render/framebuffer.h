// SPDX-License-Identifier: GPL-2.0-or-later
// The renderer's offscreen render targets (OpenGL framebuffer objects), private to render/.
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <string>
#include <vector>

#include "icgp/render/egl_context.h"

namespace icgp {

/// Pixels to which the sides of the framebuffers of render() are rounded up.
constexpr int kFramebufferGranule = 64;

/// Offscreen render targets of one image size; multisampled when `samples` > 0.
struct Framebuffer {
  GLuint fbo = 0;
  std::vector<GLuint> color;
  GLuint depth_buffer = 0;

  Framebuffer(int width, int height, const std::vector<GLenum>& color_formats, int samples = 0)
      : color(color_formats.size()) {
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(static_cast<GLsizei>(color.size()), color.data());
    for (std::size_t i = 0; i < color.size(); ++i) {
      glBindRenderbuffer(GL_RENDERBUFFER, color[i]);
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, color_formats[i], width, height);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), GL_RENDERBUFFER,
                                color[i]);
    }
    glGenRenderbuffers(1, &depth_buffer);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT32F, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RenderError("offscreen framebuffer of " + std::to_string(width) + "x" + std::to_string(height) +
                        (samples > 0 ? " with " + std::to_string(samples) + " samples" : std::string()) +
                        " is incomplete");
  }
  ~Framebuffer() {
    glDeleteRenderbuffers(static_cast<GLsizei>(color.size()), color.data());
    glDeleteRenderbuffers(1, &depth_buffer);
    glDeleteFramebuffers(1, &fbo);
  }
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;
};

}  // namespace icgp
