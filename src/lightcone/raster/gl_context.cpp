#include "lightcone/raster/gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fmt/format.h>

#include <cstring>

#include "lightcone/raster/gl.hpp"

namespace lightcone {

struct HeadlessGlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  ~Impl() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + 1, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Mesa's surfaceless platform needs no X server and no device node; any other driver gets the
// default display.
EGLDisplay open_display() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display != nullptr) {
      EGLDisplay d =
          get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
    }
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
  return EGL_NO_DISPLAY;
}

}  // namespace

HeadlessGlContext::HeadlessGlContext() : impl_(std::make_unique<Impl>()) {
  impl_->display = open_display();
  if (impl_->display == EGL_NO_DISPLAY)
    throw GlUnavailable(fmt::format("no EGL display (EGL error 0x{:x})", eglGetError()));
  if (!has_extension(eglQueryString(impl_->display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    throw GlUnavailable("the EGL display cannot make a context current without a surface");
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(impl_->display, config_attributes, &config, 1, &count) || count == 0)
    throw GlUnavailable("no EGL configuration for desktop OpenGL");
  if (!eglBindAPI(EGL_OPENGL_API)) throw GlUnavailable("EGL cannot bind desktop OpenGL");
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                       3,
                                       EGL_CONTEXT_MINOR_VERSION,
                                       3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  impl_->context = eglCreateContext(impl_->display, config, EGL_NO_CONTEXT, context_attributes);
  if (impl_->context == EGL_NO_CONTEXT)
    throw GlUnavailable(
        fmt::format("no OpenGL 3.3 core context (EGL error 0x{:x})", eglGetError()));
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context))
    throw GlUnavailable(
        fmt::format("cannot make the OpenGL context current (EGL error 0x{:x})", eglGetError()));
}

HeadlessGlContext::~HeadlessGlContext() = default;

std::string HeadlessGlContext::description() const {
  return gl_description();
}

}  // namespace lightcone
