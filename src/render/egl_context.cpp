// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

namespace icgp {
namespace {

std::string egl_error_string(EGLint code) {
  if (code == EGL_SUCCESS) return "EGL reported no error code";
  std::ostringstream s;
  s << "EGL error 0x" << std::hex << code;
  return s.str();
}

bool has_extension(const char* extensions, const char* name) {
  if (!extensions) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(extensions, name); p; p = std::strstr(p + n, name))
    if ((p == extensions || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

EGLDisplay initialise(EGLDisplay display) {
  if (display == EGL_NO_DISPLAY) return EGL_NO_DISPLAY;
  EGLint major = 0, minor = 0;
  return eglInitialize(display, &major, &minor) ? display : EGL_NO_DISPLAY;
}

// Surfaceless Mesa first (llvmpipe or a GPU, no display server needed); otherwise any EGL
// device, which is how headless GPU drivers without a surfaceless platform expose themselves.
EGLDisplay open_headless_display() {
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client_extensions)
    throw RenderError(
        "EGL is unavailable (no client extensions: is libegl1 with a vendor library such as libegl-mesa0 "
        "installed?)");
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) throw RenderError("EGL lacks eglGetPlatformDisplayEXT: cannot open a headless display");

  if (has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = initialise(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    if (d != EGL_NO_DISPLAY) return d;
  }
  if (has_extension(client_extensions, "EGL_EXT_platform_device")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLint count = 0;
    if (query_devices && query_devices(0, nullptr, &count) && count > 0) {
      std::vector<EGLDeviceEXT> devices(count);
      query_devices(count, devices.data(), &count);
      for (EGLDeviceEXT device : devices) {
        EGLDisplay d = initialise(get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr));
        if (d != EGL_NO_DISPLAY) return d;
      }
    }
  }
  throw RenderError("no headless EGL display: neither the surfaceless platform nor an EGL device could be " +
                    std::string("initialised (") + egl_error_string(eglGetError()) +
                    "); install Mesa's EGL driver (libegl-mesa0, libgl1-mesa-dri)");
}

std::atomic<SoftwareRasterThreads> raster_threads{SoftwareRasterThreads::kCallingThread};
std::atomic<bool> display_opened{false};

// One display for the process; contexts are per thread. Initialised on first use, with the
// raster threads chosen by then (Mesa reads LP_NUM_THREADS when the display opens).
EGLDisplay shared_display() {
  static const EGLDisplay display = [] {
    display_opened = true;
    if (raster_threads == SoftwareRasterThreads::kCallingThread) ::setenv("LP_NUM_THREADS", "0", /*overwrite=*/0);
    return open_headless_display();
  }();
  return display;
}

EGLConfig choose_config(EGLDisplay display) {
  if (has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context"))
    return EGL_NO_CONFIG_KHR;
  const EGLint attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint n = 0;
  if (!eglChooseConfig(display, attributes, &config, 1, &n) || n < 1)
    throw RenderError("EGL offers no OpenGL-renderable configuration (" + egl_error_string(eglGetError()) + ")");
  return config;
}

}  // namespace

bool choose_software_raster_threads(SoftwareRasterThreads threads) {
  if (display_opened) return false;
  raster_threads = threads;
  return true;
}

EglContext::EglContext() {
  EGLDisplay display = shared_display();
  if (!has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    throw RenderError("the EGL display does not support surfaceless contexts (EGL_KHR_surfaceless_context)");
  if (!eglBindAPI(EGL_OPENGL_API)) throw RenderError("EGL cannot bind the desktop OpenGL API");
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, choose_config(display), EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT)
    throw RenderError("cannot create an OpenGL 3.3 core context through EGL (" + egl_error_string(eglGetError()) +
                      ")");
  display_ = display;
  context_ = context;
  make_current();
}

EglContext::~EglContext() {
  if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
}

void EglContext::make_current() {
  if (eglGetCurrentContext() == context_) return;
  eglBindAPI(EGL_OPENGL_API);  // the bound API is per-thread state
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
    throw RenderError("cannot make the EGL context current on this thread (" + egl_error_string(eglGetError()) +
                      "): is it current on another thread? Use one renderer per thread");
}

std::string EglContext::description() const {
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return std::string("OpenGL ") + (version ? version : "?") + " | " + (renderer ? renderer : "?");
}

}  // namespace icgp
