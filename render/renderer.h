// Renders meshes with GPU materials from a calibrated camera (geometry::Intrinsics +
// geometry::CameraPose, OpenCV conventions, pixel centres at integer coordinates) into a linear
// float target, so a rendering reproduces a capture's geometry exactly. Needs a current GlContext.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "brdf/brdf.h"
#include "geometry/camera.h"
#include "render/gpu_material.h"
#include "render/mesh.h"

namespace brdfrig::render {

struct PointLight {
  brdf::Vec3 position = brdf::Vec3::Zero();  // world, metres
  brdf::Rgb intensity = brdf::Rgb::Ones();   // W/sr per channel
};

struct View {
  geometry::Intrinsics intrinsics;  // distortion is not applied (pinhole rendering)
  geometry::CameraPose pose;
  double near = 0.01, far = 20;  // metres
};

struct DrawItem {
  const GpuMesh* mesh = nullptr;
  const GpuMaterial* material = nullptr;
};

// OpenGL clip-space transform for a pinhole camera, matching geometry::ProjectToPixel (no
// distortion) with the image's row 0 at the top after Renderer's read-back.
Eigen::Matrix4f ClipFromWorld(const View& view);

class Renderer {
 public:
  Renderer(int width, int height);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws into the float target (depth-tested). Lights beyond kMaxLights are an error.
  void Draw(const View& view, const std::vector<PointLight>& lights,
            const std::vector<DrawItem>& items);
  // Waits for the GPU (for timing).
  void Finish() const;
  // The float target as radiance, CV_32FC3 in OpenCV B, G, R order, row 0 at the top.
  cv::Mat ReadRadiance() const;
  // Tone-mapped display of the float target into the window's framebuffer at column x
  // (viewer only).
  void PresentToneMapped(int x, int window_width, int window_height, float exposure);

  GLuint color_texture() const { return color_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  GLuint fbo_ = 0, color_ = 0, depth_ = 0, empty_vao_ = 0;
  std::unique_ptr<GlProgram> tonemap_;
  std::unique_ptr<GlProgram> depth_only_;
};

}  // namespace brdfrig::render
