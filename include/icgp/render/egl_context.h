// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <stdexcept>
#include <string>

namespace icgp {

/// Raised when no headless OpenGL context can be created (no EGL, no usable driver).
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A headless OpenGL 3.3+ core context through EGL: Mesa's surfaceless platform first,
/// an EGL device (e.g. a GPU without a display) as fallback. No window, no X.
/// A context belongs to the thread that uses it: create one per rendering thread.
class EglContext {
 public:
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// Binds the context to the calling thread (cheap when already current).
  void make_current();
  /// "OpenGL 4.5 (Core Profile) Mesa ... | llvmpipe ..." for logs.
  std::string description() const;

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

}  // namespace icgp
