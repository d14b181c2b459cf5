#include "render/gpu_material.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/check.h"
#include "common/error.h"

namespace brdfrig::render {
namespace {

std::vector<std::string> Defines(const std::string& material) {
  return {"MAX_SLICES " + std::to_string(kMaxSlices), "MAX_LIGHTS " + std::to_string(kMaxLights),
          material};
}

Eigen::Vector3f ToFloat(const brdf::Rgb& c) { return c.cast<float>().matrix(); }

}  // namespace

std::unique_ptr<GpuMaterial> GpuMaterial::SliceModel(const brdf::SliceModel& model) {
  const auto& slices = model.slices();
  if (slices.size() > kMaxSlices) {
    throw Error("the renderer supports at most " + std::to_string(kMaxSlices) +
                " slices, model has " + std::to_string(slices.size()));
  }
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kSlice;
  m->program_ = std::make_unique<GlProgram>(
      std::vector<std::string>{"mesh.vert"},
      std::vector<std::string>{"slice_model.glsl", "shade.frag"}, Defines("MATERIAL_SLICE"));
  // std140 layout of SliceBlock (shaders/slice_model.glsl).
  std::vector<float> block(4 * 4 * kMaxSlices + kMaxSlices + 4, 0.0f);
  for (std::size_t k = 0; k < slices.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      const brdf::LobeParams& q = slices[k].channel[c];
      // log2(e)/h: the shader then needs one multiply and exp2, no divide (clamped to the
      // float range so that a tiny h stays a finite, very steep step).
      const double values[4] = {q.a1, q.a2, std::min(M_LOG2E / q.h, 1e38), q.x0};
      for (int p = 0; p < 4; ++p) block[16 * k + 4 * p + c] = static_cast<float>(values[p]);
    }
    block[16 * kMaxSlices + k] = static_cast<float>(slices[k].theta_in);
  }
  m->slice_count_ = static_cast<int>(slices.size());
  m->block_ = std::move(block);
  glCreateBuffers(1, &m->buffer_);
  m->UploadSliceBlock();
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::Lambert(const brdf::Rgb& albedo) {
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kLambert;
  m->albedo_ = albedo;
  m->program_ = std::make_unique<GlProgram>(
      std::vector<std::string>{"mesh.vert"},
      std::vector<std::string>{"reference_brdfs.glsl", "shade.frag"}, Defines("MATERIAL_LAMBERT"));
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::Ggx(const brdf::MicrofacetParams& params) {
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kGgx;
  m->ggx_ = params;
  m->program_ = std::make_unique<GlProgram>(
      std::vector<std::string>{"mesh.vert"},
      std::vector<std::string>{"reference_brdfs.glsl", "shade.frag"}, Defines("MATERIAL_GGX"));
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::Merl(const brdf::MerlTable& table) {
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kMerl;
  m->program_ = std::make_unique<GlProgram>(
      std::vector<std::string>{"mesh.vert"},
      std::vector<std::string>{"reference_brdfs.glsl", "shade.frag"}, Defines("MATERIAL_MERL"));
  // Interleave the channel blocks and apply MERL's per-channel scales (docs/design.md, formats).
  constexpr double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};
  std::vector<float> rgb(3 * static_cast<std::size_t>(brdf::kMerlBins));
  for (std::size_t i = 0; i < static_cast<std::size_t>(brdf::kMerlBins); ++i) {
    for (int c = 0; c < 3; ++c) {
      rgb[3 * i + c] = static_cast<float>(table.data()[c * brdf::kMerlBins + i] * kScale[c]);
    }
  }
  glCreateTextures(GL_TEXTURE_3D, 1, &m->texture_);
  m->texture_target_ = GL_TEXTURE_3D;
  glTextureStorage3D(m->texture_, 1, GL_RGB32F, brdf::kMerlPhiD, brdf::kMerlThetaD,
                     brdf::kMerlThetaH);
  glTextureSubImage3D(m->texture_, 0, 0, 0, 0, brdf::kMerlPhiD, brdf::kMerlThetaD,
                      brdf::kMerlThetaH, GL_RGB, GL_FLOAT, rgb.data());
  return m;
}

GpuMaterial::~GpuMaterial() {
  if (texture_) glDeleteTextures(1, &texture_);
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

void GpuMaterial::UploadSliceBlock() {
  // The two ints after the float arrays: slice count and the linear-interpolation flag.
  const std::size_t ints = 16 * kMaxSlices + kMaxSlices;
  const int flags[2] = {slice_count_, linear_ ? 1 : 0};
  std::memcpy(&block_[ints], flags, sizeof(flags));
  glNamedBufferData(buffer_, static_cast<GLsizeiptr>(block_.size() * sizeof(float)), block_.data(),
                    GL_DYNAMIC_DRAW);
}

void GpuMaterial::SetLinearInterpolation(bool linear) {
  linear_ = linear;
  if (kind_ == Kind::kSlice) UploadSliceBlock();
}

void GpuMaterial::Bind() const {
  program_->Use();
  if (texture_) glBindTextureUnit(0, texture_);
  switch (kind_) {
    case Kind::kSlice:
      glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffer_);
      break;
    case Kind::kLambert:
      program_->Set("uAlbedo", ToFloat(albedo_));
      break;
    case Kind::kGgx:
      program_->Set("uDiffuse", ToFloat(ggx_.diffuse));
      program_->Set("uF0", ToFloat(ggx_.f0));
      program_->Set("uAlpha", static_cast<float>(ggx_.alpha));
      break;
    case Kind::kMerl:
      program_->Set("uMerl", 0);
      break;
  }
}

cv::Mat EvalSliceModelOnGpu(const brdf::SliceModel& model, const cv::Mat& angles, bool linear) {
  BRDFRIG_CHECK(angles.type() == CV_32FC2 && !angles.empty(),
                "EvalSliceModelOnGpu: angles must be a non-empty CV_32FC2 image");
  std::unique_ptr<GpuMaterial> material = GpuMaterial::SliceModel(model);
  material->SetLinearInterpolation(linear);
  GlProgram grid({"grid.vert"}, {"slice_model.glsl", "grid.frag"}, Defines("MATERIAL_SLICE"));
  const cv::Mat input = angles.isContinuous() ? angles : angles.clone();
  GLuint textures[2], fbo, vao;
  glCreateTextures(GL_TEXTURE_2D, 2, textures);
  glTextureStorage2D(textures[0], 1, GL_RG32F, input.cols, input.rows);
  glTextureSubImage2D(textures[0], 0, 0, 0, input.cols, input.rows, GL_RG, GL_FLOAT, input.data);
  glTextureStorage2D(textures[1], 1, GL_RGBA32F, input.cols, input.rows);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, textures[1], 0);
  glCreateVertexArrays(1, &vao);

  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, input.cols, input.rows);
  glDisable(GL_DEPTH_TEST);
  grid.Use();
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, material->buffer_);
  glBindTextureUnit(1, textures[0]);
  grid.Set("uAngles", 1);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  cv::Mat rgba(input.rows, input.cols, CV_32FC4);
  glReadPixels(0, 0, input.cols, input.rows, GL_RGBA, GL_FLOAT, rgba.data);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vao);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(2, textures);
  cv::Mat rgb(input.rows, input.cols, CV_32FC3);
  const int from_to[] = {0, 0, 1, 1, 2, 2};
  cv::mixChannels(&rgba, 1, &rgb, 1, from_to, 3);
  return rgb;
}

}  // namespace brdfrig::render
