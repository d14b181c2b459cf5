#include "render/gpu_material.h"

#include <opencv2/core.hpp>

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
  std::vector<float> texels;  // 4 parameters × slices, RGBA
  for (const brdf::Slice& s : slices) {
    m->knots_.push_back(static_cast<float>(s.theta_in));
    for (int p = 0; p < 4; ++p) {
      for (int c = 0; c < 3; ++c) {
        const brdf::LobeParams& q = s.channel[c];
        const double values[4] = {q.a1, q.a2, q.h, q.x0};
        texels.push_back(static_cast<float>(values[p]));
      }
      texels.push_back(0);
    }
  }
  glCreateTextures(GL_TEXTURE_2D, 1, &m->texture_);
  m->texture_target_ = GL_TEXTURE_2D;
  glTextureStorage2D(m->texture_, 1, GL_RGBA32F, 4, static_cast<GLsizei>(slices.size()));
  glTextureSubImage2D(m->texture_, 0, 0, 0, 4, static_cast<GLsizei>(slices.size()), GL_RGBA,
                      GL_FLOAT, texels.data());
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
  // Interleave the channel blocks and apply MERL's per-channel scales (REFERENCE.md).
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
}

void GpuMaterial::Bind() const {
  program_->Use();
  if (texture_) glBindTextureUnit(0, texture_);
  switch (kind_) {
    case Kind::kSlice:
      program_->Set("uSlices", 0);
      program_->Set("uSliceCount", static_cast<int>(knots_.size()));
      program_->Set("uLinear", linear_ ? 1 : 0);
      glUniform1fv(program_->Location("uKnots"), static_cast<GLsizei>(knots_.size()),
                   knots_.data());
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
  if (angles.type() != CV_32FC2 || angles.empty()) {
    throw Error("EvalSliceModelOnGpu: angles must be a non-empty CV_32FC2 image");
  }
  std::unique_ptr<GpuMaterial> material = GpuMaterial::SliceModel(model);
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
  glBindTextureUnit(0, material->texture_);
  glBindTextureUnit(1, textures[0]);
  grid.Set("uSlices", 0);
  grid.Set("uAngles", 1);
  grid.Set("uSliceCount", static_cast<int>(material->knots_.size()));
  grid.Set("uLinear", linear ? 1 : 0);
  glUniform1fv(grid.Location("uKnots"), static_cast<GLsizei>(material->knots_.size()),
               material->knots_.data());
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
