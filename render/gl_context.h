// An OpenGL 4.5 core context, obtained one of two ways: headless through EGL (Mesa's
// surfaceless platform, which runs on llvmpipe where there is no GPU, or an EGL device where
// there is one), or in a window through GLFW. The renderer does not care which.
#pragma once

#include <memory>
#include <string>

struct GLFWwindow;

namespace brdfrig::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void MakeCurrent() = 0;
  // Renderer and version strings, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core Profile)".
  std::string Description() const;
};

// Throws brdfrig::Error saying what failed (no EGL display, no OpenGL 4.5 core, ...).
std::unique_ptr<GlContext> CreateHeadlessContext();

class WindowContext : public GlContext {
 public:
  WindowContext(int width, int height, const std::string& title);
  ~WindowContext() override;
  void MakeCurrent() override;
  GLFWwindow* window() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace brdfrig::render
