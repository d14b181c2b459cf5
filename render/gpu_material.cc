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
          "MAX_TABLE_KNOTS " + std::to_string(kMaxTableKnots),
          "MAX_FRESNEL_KNOTS " + std::to_string(kMaxFresnelKnots), material};
}

const char* MicrofacetDefine(brdf::Distribution d) {
  switch (d) {
    case brdf::Distribution::kGgx:
      return "MICROFACET_GGX";
    case brdf::Distribution::kBeckmann:
      return "MICROFACET_BECKMANN";
    case brdf::Distribution::kTable:
      return "MICROFACET_TABLE";
  }
  return "";
}

// std140 contents of MicrofacetBlock (shaders/microfacet_model.glsl). Everything the shader
// would otherwise recompute per pixel is derived here, in double.
std::vector<float> MicrofacetBlock(const brdf::MicrofacetModel& model) {
  const brdf::MicrofacetModelParams& p = model.params();
  const std::vector<double>& log_d = model.normalized_log_d();
  if (log_d.size() > static_cast<std::size_t>(kMaxTableKnots) ||
      p.fresnel_knots.size() > static_cast<std::size_t>(kMaxFresnelKnots)) {
    throw Error("the renderer supports at most " + std::to_string(kMaxTableKnots) +
                " table knots and " + std::to_string(kMaxFresnelKnots) +
                " Fresnel knots, model has " + std::to_string(log_d.size()) + " and " +
                std::to_string(p.fresnel_knots.size()));
  }
  std::vector<float> block(kMaxTableKnots + kMaxFresnelKnots + 5 * 4, 0.0f);
  for (std::size_t k = 0; k < log_d.size(); ++k) block[k] = static_cast<float>(log_d[k]);
  float* fresnel = &block[kMaxTableKnots];
  for (std::size_t k = 0; k < p.fresnel_knots.size(); ++k) {
    fresnel[k] = static_cast<float>(p.fresnel_knots[k]);
  }
  float* tail = fresnel + kMaxFresnelKnots;
  float* diffuse = tail;
  float* f0 = tail + 4;
  float* roughness = tail + 8;
  float* table = tail + 12;
  float* fresnel_scale = tail + 16;
  for (int c = 0; c < 3; ++c) {
    diffuse[c] = static_cast<float>(p.diffuse[c] / M_PI);
    f0[c] = static_cast<float>(p.f0[c]);
  }
  const bool is_table = p.distribution == brdf::Distribution::kTable;
  const double a2 = p.alpha * p.alpha;
  roughness[0] = static_cast<float>(a2);
  roughness[1] = static_cast<float>(is_table ? p.shadowing_alpha * p.shadowing_alpha : a2);
  roughness[2] = static_cast<float>(p.alpha);
  if (is_table) {
    const double knots = static_cast<double>(log_d.size());
    const double c = std::cos(p.max_theta_h), s = std::sin(p.max_theta_h);
    table[0] = static_cast<float>(1 / p.max_theta_h);
    table[1] = static_cast<float>(knots - 1);
    table[2] = static_cast<float>(p.max_theta_h);
    const double denom = a2 * c * c + s * s;
    table[3] = static_cast<float>(std::min(std::exp(log_d.back()) * denom * denom, 1e38));
  }
  const double fresnel_count = static_cast<double>(p.fresnel_knots.size());
  fresnel_scale[0] = static_cast<float>(fresnel_count);
  fresnel_scale[1] = static_cast<float>(std::max(fresnel_count - 1, 0.0) / (M_PI / 2));
  return block;
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
  m->Build({"slice_model.glsl"}, Defines("MATERIAL_SLICE"));
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
  m->Build({"reference_brdfs.glsl"}, Defines("MATERIAL_LAMBERT"));
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::Ggx(const brdf::MicrofacetParams& params) {
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kGgx;
  m->ggx_ = params;
  m->Build({"reference_brdfs.glsl"}, Defines("MATERIAL_GGX"));
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::Merl(const brdf::MerlTable& table) {
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kMerl;
  m->Build({"reference_brdfs.glsl"}, Defines("MATERIAL_MERL"));
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

std::unique_ptr<GpuMaterial> GpuMaterial::Microfacet(const brdf::MicrofacetModel& model) {
  const std::vector<float> block = MicrofacetBlock(model);
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kMicrofacet;
  m->Build({"microfacet_model.glsl"}, Defines(MicrofacetDefine(model.params().distribution)));
  glCreateBuffers(1, &m->buffer_);
  glNamedBufferData(m->buffer_, static_cast<GLsizeiptr>(block.size() * sizeof(float)), block.data(),
                    GL_STATIC_DRAW);
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::Table(const brdf::RusinkiewiczTable& table) {
  const brdf::RusinkiewiczGrid& grid = table.grid();
  const brdf::TableValues& q = table.values();
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kTable;
  m->table_grid_ = grid;
  m->Build({"rusinkiewicz_table.glsl"}, Defines("MATERIAL_TABLE"));
  // An RGBA32F buffer texture in node order (the shader's eight texelFetch reads cost about
  // half of a 3D texture's on llvmpipe); GL guarantees only 65536 texels.
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (grid.Cells() > max_texels) {
    throw Error("the renderer's GL supports tables of at most " + std::to_string(max_texels) +
                " nodes, the table has " + std::to_string(grid.Cells()));
  }
  const std::size_t cells = static_cast<std::size_t>(grid.Cells());
  std::vector<float> rgba(4 * cells, 0.0f);
  for (std::size_t i = 0; i < cells; ++i) {
    for (int c = 0; c < 3; ++c) rgba[4 * i + c] = static_cast<float>(q[c][i]);
  }
  glCreateBuffers(1, &m->buffer_);
  glNamedBufferData(m->buffer_, static_cast<GLsizeiptr>(rgba.size() * sizeof(float)), rgba.data(),
                    GL_STATIC_DRAW);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &m->texture_);
  m->texture_target_ = GL_TEXTURE_BUFFER;
  glTextureBuffer(m->texture_, GL_RGBA32F, m->buffer_);
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::Gltf(const brdf::GltfModel& model) {
  std::unique_ptr<GpuMaterial> m(new GpuMaterial);
  m->kind_ = Kind::kGltf;
  m->gltf_ = model.params();
  m->Build({"gltf_model.glsl"}, Defines("MATERIAL_GLTF"));
  return m;
}

std::unique_ptr<GpuMaterial> GpuMaterial::ForBrdf(const brdf::Brdf& brdf) {
  if (const auto* slices = dynamic_cast<const brdf::SliceModel*>(&brdf)) {
    return SliceModel(*slices);
  }
  if (const auto* microfacet = dynamic_cast<const brdf::MicrofacetModel*>(&brdf)) {
    return Microfacet(*microfacet);
  }
  if (const auto* lambert = dynamic_cast<const brdf::Lambert*>(&brdf)) {
    return Lambert(lambert->albedo());
  }
  if (const auto* ggx = dynamic_cast<const brdf::Ggx*>(&brdf)) return Ggx(ggx->params());
  if (const auto* table = dynamic_cast<const brdf::MerlTable*>(&brdf)) return Merl(*table);
  if (const auto* table = dynamic_cast<const brdf::RusinkiewiczTable*>(&brdf)) return Table(*table);
  if (const auto* gltf = dynamic_cast<const brdf::GltfModel*>(&brdf)) return Gltf(*gltf);
  return Merl(brdf::MerlTable::Tabulate(brdf));
}

std::unique_ptr<GpuMaterial> GpuMaterial::ForMaterial(const brdf::Material& material) {
  if (brdf::IsSliceKind(material.kind)) return SliceModel(material.Slices());
  if (material.kind == brdf::ModelKind::kPrior) {
    return Table(brdf::RusinkiewiczTable(material.table_grid, material.table));
  }
  return ForBrdf(*material.Model());
}

void GpuMaterial::Build(std::vector<std::string> files, std::vector<std::string> defines) {
  files_ = std::move(files);
  defines_ = std::move(defines);
  program_ = MakeProgram("mesh.vert", "shade.frag");
}

std::unique_ptr<GlProgram> GpuMaterial::MakeProgram(const std::string& vertex_file,
                                                    const std::string& main_file) const {
  std::vector<std::string> fragment = files_;
  fragment.push_back(main_file);
  return std::make_unique<GlProgram>(std::vector<std::string>{vertex_file}, fragment, defines_);
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

void GpuMaterial::Bind(const GlProgram& program) const {
  program.Use();
  if (texture_) glBindTextureUnit(0, texture_);
  switch (kind_) {
    case Kind::kSlice:
    case Kind::kMicrofacet:
      glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffer_);
      break;
    case Kind::kLambert:
      program.Set("uAlbedo", ToFloat(albedo_));
      break;
    case Kind::kGgx:
      program.Set("uDiffuse", ToFloat(ggx_.diffuse));
      program.Set("uF0", ToFloat(ggx_.f0));
      program.Set("uAlpha", static_cast<float>(ggx_.alpha));
      break;
    case Kind::kMerl:
      program.Set("uMerl", 0);
      break;
    case Kind::kGltf: {
      const brdf::GltfParams& p = gltf_;
      const double alpha = p.roughness * p.roughness;
      program.Set("uGltfBase", ToFloat(p.base_color));
      program.Set("uGltfDiffuse", ToFloat(p.base_color / M_PI));
      program.Set("uGltfF0", ToFloat(p.DielectricF0()));
      program.Set("uGltfMetallic", static_cast<float>(p.metallic));
      program.Set("uGltfSpecular", static_cast<float>(p.specular));
      program.Set("uGltfAlpha2", static_cast<float>(alpha * alpha));
      break;
    }
    case Kind::kTable: {
      const brdf::RusinkiewiczGrid& g = table_grid_;
      program.Set("uTable", 0);
      // In double, then rounded once: the index scales the CPU computes in StencilAt.
      program.Set("uTableScale",
                  Eigen::Vector3f(static_cast<float>((g.phi_d - 1) / (M_PI / 2)),
                                  static_cast<float>((g.theta_d - 1) / (M_PI / 2)),
                                  static_cast<float>((g.theta_h - 1) / std::sqrt(M_PI / 2))));
      program.Set("uTableLast", Eigen::Vector3f(static_cast<float>(g.phi_d - 1),
                                                static_cast<float>(g.theta_d - 1),
                                                static_cast<float>(g.theta_h - 1)));
      program.Set("uTableStrideD", g.phi_d);
      program.Set("uTableStrideH", g.theta_d * g.phi_d);
      program.Set("uTableEpsilon", static_cast<float>(g.epsilon));
      program.Set("uTableCosFloor", static_cast<float>(g.cos_floor));
      break;
    }
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
