#include "render/material_probe.h"

#include "common/error.h"

namespace brdfrig::render {

cv::Mat EvalMaterialOnGpu(const GpuMaterial& material, const cv::Mat& light, const cv::Mat& view,
                          const Eigen::Vector3f& normal) {
  if (light.type() != CV_32FC3 || view.type() != CV_32FC3 || light.empty() ||
      light.size() != view.size()) {
    throw Error("EvalMaterialOnGpu: light and view must be non-empty CV_32FC3 images of one size");
  }
  const std::unique_ptr<GlProgram> probe =
      material.MakeProgram("grid.vert", "direction_probe.frag");
  const int width = light.cols, height = light.rows;
  GLuint textures[3], fbo, vao;
  glCreateTextures(GL_TEXTURE_2D, 3, textures);
  const cv::Mat inputs[2] = {light.isContinuous() ? light : light.clone(),
                             view.isContinuous() ? view : view.clone()};
  for (int i = 0; i < 2; ++i) {
    glTextureStorage2D(textures[i], 1, GL_RGB32F, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(textures[i], 0, 0, 0, width, height, GL_RGB, GL_FLOAT, inputs[i].data);
  }
  glTextureStorage2D(textures[2], 1, GL_RGBA32F, width, height);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, textures[2], 0);
  glCreateVertexArrays(1, &vao);

  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  material.Bind(*probe);
  // Units 1 and 2: unit 0 belongs to materials with a texture.
  glBindTextureUnit(1, textures[0]);
  glBindTextureUnit(2, textures[1]);
  probe->Set("uLight", 1);
  probe->Set("uView", 2);
  probe->Set("uNormal", normal);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  cv::Mat rgba(height, width, CV_32FC4);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vao);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(3, textures);
  cv::Mat rgb(height, width, CV_32FC3);
  const int from_to[] = {0, 0, 1, 1, 2, 2};
  cv::mixChannels(&rgba, 1, &rgb, 1, from_to, 3);
  return rgb;
}

}  // namespace brdfrig::render
