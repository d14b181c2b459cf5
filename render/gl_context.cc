#include "render/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
// After epoxy, and without GLFW pulling in its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>

#include "common/error.h"

namespace brdfrig::render {
namespace {

class EglContext : public GlContext {
 public:
  EglContext() {
    // Prefer Mesa's surfaceless platform: it needs no X server, no GBM device, no GPU.
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
      display_ =
          eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    }
    if (display_ == EGL_NO_DISPLAY) display_ = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major = 0, minor = 0;
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor)) {
      throw Error("headless rendering: no EGL display (is Mesa's libegl-mesa0 installed?)");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      throw Error("headless rendering: EGL cannot bind desktop OpenGL");
    }
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    // Surfaceless contexts need no config; pass one if the driver offers it.
    eglChooseConfig(display_, config_attribs, &config, 1, &count);
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    context_ = eglCreateContext(display_, count > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                                context_attribs);
    if (context_ == EGL_NO_CONTEXT) {
      throw Error("headless rendering: EGL could not create an OpenGL 4.5 core context (error 0x" +
                  ToHex(eglGetError()) + ")");
    }
    MakeCurrent();
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  void MakeCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw Error("headless rendering: eglMakeCurrent failed (no surfaceless context support)");
    }
  }

 private:
  static std::string ToHex(EGLint value) {
    char buffer[16];
    std::snprintf(buffer, sizeof(buffer), "%x", static_cast<unsigned>(value));
    return buffer;
  }
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::string GlContext::Description() const {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(renderer ? renderer : "?") + " / " + (version ? version : "?");
}

std::unique_ptr<GlContext> CreateHeadlessContext() { return std::make_unique<EglContext>(); }

WindowContext::WindowContext(int width, int height, const std::string& title) {
  if (!glfwInit()) throw Error("window: GLFW could not initialise (is DISPLAY set?)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw Error("window: could not open an OpenGL 4.5 core window");
  }
  MakeCurrent();
}

WindowContext::~WindowContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void WindowContext::MakeCurrent() { glfwMakeContextCurrent(window_); }

}  // namespace brdfrig::render
