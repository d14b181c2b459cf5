#include "render/renderer.h"

#include "common/check.h"
#include "common/error.h"

namespace brdfrig::render {

Eigen::Matrix4f ClipFromWorld(const View& view) {
  const geometry::Intrinsics& k = view.intrinsics;
  const double w = k.width, h = k.height, n = view.near, f = view.far;
  // OpenCV pixel u = fx x/z + cx has its centre at GL window x = u + 0.5; rows are flipped on
  // read-back, so image row v is GL window row h - v - 1.
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  projection(0, 0) = 2 * k.fx / w;
  projection(0, 2) = (2 * k.cx + 1) / w - 1;
  projection(1, 1) = -2 * k.fy / h;
  projection(1, 2) = 1 - (2 * k.cy + 1) / h;
  projection(2, 2) = (f + n) / (f - n);
  projection(2, 3) = -2 * f * n / (f - n);
  projection(3, 2) = 1;
  return (projection * view.pose.camera_from_world.matrix()).cast<float>();
}

Renderer::Renderer(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw Error("renderer: image size must be positive");
  glCreateTextures(GL_TEXTURE_2D, 1, &color_);
  glTextureStorage2D(color_, 1, GL_RGBA32F, width, height);
  glCreateRenderbuffers(1, &depth_);
  glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT32F, width, height);
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
  glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw Error("renderer: the float render target is not supported by this OpenGL driver");
  }
  glCreateVertexArrays(1, &empty_vao_);
}

Renderer::~Renderer() {
  glDeleteVertexArrays(1, &empty_vao_);
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteTextures(1, &color_);
}

void Renderer::Draw(const View& view, const std::vector<PointLight>& lights,
                    const std::vector<DrawItem>& items) {
  if (lights.size() > static_cast<std::size_t>(kMaxLights)) {
    throw Error("renderer: at most " + std::to_string(kMaxLights) + " point lights");
  }
  BRDFRIG_CHECK(view.intrinsics.width == width_ && view.intrinsics.height == height_,
                "the view's resolution must be the render target's");
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const float clear[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(fbo_, GL_COLOR, 0, clear);
  glClear(GL_DEPTH_BUFFER_BIT);
  const Eigen::Matrix4f clip = ClipFromWorld(view);
  // Depth pre-pass: every pixel is then shaded once, whatever the overdraw.
  if (!depth_only_) {
    depth_only_ = std::make_unique<GlProgram>(std::vector<std::string>{"mesh.vert"},
                                              std::vector<std::string>{"depth.frag"},
                                              std::vector<std::string>{});
  }
  depth_only_->Use();
  depth_only_->Set("uClipFromWorld", clip);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  for (const DrawItem& item : items) item.mesh->Draw();
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);

  const Eigen::Vector3f center = view.pose.CenterInWorld().cast<float>();
  std::vector<float> positions, intensities;
  for (const PointLight& light : lights) {
    for (int c = 0; c < 3; ++c) {
      positions.push_back(static_cast<float>(light.position[c]));
      intensities.push_back(static_cast<float>(light.intensity[c]));
    }
  }
  for (const DrawItem& item : items) {
    item.material->Bind();
    const GlProgram& p = item.material->program();
    p.Set("uClipFromWorld", clip);
    p.Set("uCameraCenter", center);
    p.Set("uLightCount", static_cast<int>(lights.size()));
    if (!lights.empty()) {
      glUniform3fv(p.Location("uLightPosition"), static_cast<GLsizei>(lights.size()),
                   positions.data());
      glUniform3fv(p.Location("uLightIntensity"), static_cast<GLsizei>(lights.size()),
                   intensities.data());
    }
    item.mesh->Draw();
  }
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::Finish() const { glFinish(); }

cv::Mat Renderer::ReadRadiance() const {
  cv::Mat rgba(height_, width_, CV_32FC4);
  glGetTextureImage(color_, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.total() * 16),
                    rgba.data);
  cv::Mat bgr(height_, width_, CV_32FC3);
  const int from_to[] = {0, 2, 1, 1, 2, 0};
  cv::mixChannels(&rgba, 1, &bgr, 1, from_to, 3);
  cv::Mat flipped;
  cv::flip(bgr, flipped, 0);  // GL rows start at the bottom
  return flipped;
}

void Renderer::PresentToneMapped(int x, int window_width, int window_height, float exposure) {
  if (!tonemap_) {
    tonemap_ = std::make_unique<GlProgram>(std::vector<std::string>{"grid.vert"},
                                           std::vector<std::string>{"tonemap.frag"},
                                           std::vector<std::string>{});
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(x, 0, std::min(window_width, width_), std::min(window_height, height_));
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_FRAMEBUFFER_SRGB);
  tonemap_->Use();
  glBindTextureUnit(0, color_);
  tonemap_->Set("uRadiance", 0);
  tonemap_->Set("uExposure", exposure);
  tonemap_->Set("uOffsetX", x);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_FRAMEBUFFER_SRGB);
}

}  // namespace brdfrig::render
