#include "render/viewer.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "geometry/camera.h"
#include "render/capture_view.h"
#include "render/gl_context.h"
#include "render/renderer.h"

namespace brdfrig::render {
namespace {

struct ViewerState {
  double yaw = 0.6, pitch = 0.5, distance = 0.35;
  double light_azimuth = -0.8, light_elevation = 0.9;
  float exposure = 40.0f;
  int mesh = 1;
  bool linear = false;
  bool dragging = false, save = false;
  double last_x = 0, last_y = 0;
};

View OrbitView(const ViewerState& s, int width, int height) {
  View view;
  const double f = 1.2 * height;
  view.intrinsics = {width, height, f, f, width / 2.0, height / 2.0};
  const Eigen::Vector3d eye =
      s.distance * Eigen::Vector3d(std::cos(s.pitch) * std::sin(s.yaw),
                                   -std::cos(s.pitch) * std::cos(s.yaw), std::sin(s.pitch));
  view.pose = geometry::LookAt(eye, geometry::Vec3::Zero(), geometry::Vec3::UnitZ());
  return view;
}

void SaveScreenshot(int width, int height, const std::string& path) {
  cv::Mat rgb(height, width, CV_8UC3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_BGR, GL_UNSIGNED_BYTE, rgb.data);
  cv::Mat flipped;
  cv::flip(rgb, flipped, 0);
  if (!cv::imwrite(path, flipped)) throw Error("cannot write screenshot '" + path + "'");
  std::printf("screenshot: %s\n", path.c_str());
}

}  // namespace

void ViewerOptions::Validate() const {
  if (width < 64 || height < 64) throw OptionsError("viewer size must be at least 64x64");
  if (frames < 0) throw OptionsError("--frames must be >= 0");
}

void RunViewer(const brdf::Brdf& material, const brdf::Brdf* compare, const std::string& label,
               const std::string& compare_label, const ViewerOptions& options) {
  options.Validate();
  WindowContext context(options.width, options.height, "brdfrig view");
  GLFWwindow* window = context.window();
  ViewerState state;
  glfwSetWindowUserPointer(window, &state);
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    auto* s = static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
    if (button == GLFW_MOUSE_BUTTON_LEFT) s->dragging = action == GLFW_PRESS;
    glfwGetCursorPos(w, &s->last_x, &s->last_y);
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    auto* s = static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
    if (s->dragging) {
      s->yaw += 0.01 * (x - s->last_x);
      s->pitch = std::clamp(s->pitch + 0.01 * (y - s->last_y), 0.05, 1.5);
    }
    s->last_x = x;
    s->last_y = y;
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    auto* s = static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
    s->distance = std::clamp(s->distance * std::pow(0.9, dy), 0.1, 2.0);
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_RELEASE) return;
    auto* s = static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
    switch (key) {
      case GLFW_KEY_ESCAPE:
      case GLFW_KEY_Q:
        glfwSetWindowShouldClose(w, GLFW_TRUE);
        break;
      case GLFW_KEY_LEFT:
        s->light_azimuth -= 0.1;
        break;
      case GLFW_KEY_RIGHT:
        s->light_azimuth += 0.1;
        break;
      case GLFW_KEY_UP:
        s->light_elevation = std::min(1.5, s->light_elevation + 0.1);
        break;
      case GLFW_KEY_DOWN:
        s->light_elevation = std::max(0.05, s->light_elevation - 0.1);
        break;
      case GLFW_KEY_M:
        s->mesh = (s->mesh + 1) % 3;
        break;
      case GLFW_KEY_I:
        s->linear = !s->linear;
        break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD:
        s->exposure *= 1.25f;
        break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT:
        s->exposure /= 1.25f;
        break;
      case GLFW_KEY_S:
        s->save = true;
        break;
      default:
        break;
    }
  });

  const GpuMesh meshes[3] = {GpuMesh(MakeSphere(0.06f, 96, 192)), GpuMesh(MakeTestObject(50000)),
                             GpuMesh(MakeRectangle(-0.1f, 0.1f, -0.1f, 0.1f))};
  const char* mesh_names[3] = {"sphere", "50K-triangle object", "plane"};
  std::unique_ptr<GpuMaterial> left = MakeGpuMaterial(material);
  std::unique_ptr<GpuMaterial> right = compare ? MakeGpuMaterial(*compare) : nullptr;
  const int panes = right ? 2 : 1;
  const int pane_width = options.width / panes;
  Renderer renderer(pane_width, options.height);

  int frame = 0;
  auto last = std::chrono::steady_clock::now();
  double fps = 0;
  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    const View view = OrbitView(state, pane_width, options.height);
    const PointLight light{
        0.4 * Eigen::Vector3d(std::cos(state.light_elevation) * std::cos(state.light_azimuth),
                              std::cos(state.light_elevation) * std::sin(state.light_azimuth),
                              std::sin(state.light_elevation)),
        brdf::Rgb::Constant(0.02)};
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glClearColor(0.1f, 0.1f, 0.1f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    for (int p = 0; p < panes; ++p) {
      GpuMaterial& m = p == 0 ? *left : *right;
      m.SetLinearInterpolation(state.linear);
      renderer.Draw(view, {light}, {{&meshes[state.mesh], &m}});
      glViewport(p * pane_width, 0, pane_width, options.height);
      renderer.PresentToneMapped(p * pane_width, pane_width, options.height, state.exposure);
    }
    ++frame;
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    fps = fps == 0 ? 1 / dt : 0.9 * fps + 0.1 / dt;
    char title[256];
    std::snprintf(title, sizeof(title), "brdfrig view — %s%s%s — %s — %s — %.1f fps", label.c_str(),
                  right ? " | " : "", right ? compare_label.c_str() : "", mesh_names[state.mesh],
                  state.linear ? "linear (seams)" : "C1 spline", fps);
    glfwSetWindowTitle(window, title);
    if (state.save || (options.frames > 0 && frame == options.frames)) {
      SaveScreenshot(options.width, options.height, options.screenshot_path);
      state.save = false;
    }
    glfwSwapBuffers(window);
    if (options.frames > 0 && frame >= options.frames) break;
  }
}

}  // namespace brdfrig::render
