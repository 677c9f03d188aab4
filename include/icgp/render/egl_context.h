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

/// How Mesa's software rasteriser (llvmpipe, the renderer when there is no GPU) spreads a
/// render over threads. It reads LP_NUM_THREADS once, when the process's EGL display is
/// opened (the first EglContext), so one choice holds for the whole process, and a
/// LP_NUM_THREADS the user set always wins. A GPU driver ignores it.
enum class SoftwareRasterThreads {
  /// Each render on the thread that asks for it (LP_NUM_THREADS=0), the default. A
  /// tracker's renders are crops of a few thousand pixels, for which handing the raster work
  /// to other threads and waiting for them costs more than it saves: with depth alone on
  /// teabox-blender (a render a frame) the render step took 0.07–0.12 ms instead of
  /// 0.17–0.21 ms, and ViSP's depth-only castle program 2.54 instead of 2.90 ms a frame
  /// (medians of 6 runs each). Model generation renders on one thread per core itself (with
  /// llvmpipe's threads on top, `icgp model` took 22 s instead of 17 s for the default
  /// models).
  kCallingThread,
  /// llvmpipe's own default, a raster thread per core: for whole frames, as the servo
  /// simulator and make-sequence render them (the default servo scenario ran in 10.4 s
  /// with them and 12.2 s without).
  kPerCore,
};

/// Makes `threads` the choice for when the display is opened. Returns false, and changes
/// nothing, once it is open. Call it before anything renders, from one thread.
bool choose_software_raster_threads(SoftwareRasterThreads threads);

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
