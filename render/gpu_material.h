// A material on the GPU: its shading program and parameters. The slice model's slices go to a
// small uniform buffer (4 parameters × slices, rgb = channels, plus the knots); so do the
// microfacet rungs' parameters (their ln D table, Fresnel knots, colours and roughness). The
// prior's Rusinkiewicz table goes to a float buffer texture of its node values q.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "brdf/analytic.h"
#include "brdf/gltf_model.h"
#include "brdf/material_file.h"
#include "brdf/merl.h"
#include "brdf/microfacet_model.h"
#include "brdf/rusinkiewicz_table.h"
#include "brdf/slice_model.h"
#include "render/gl_program.h"

namespace brdfrig::render {

inline constexpr int kMaxSlices = brdf::kMaxSlices;  // the material's own limit
inline constexpr int kMaxLights = 8;
// The microfacet table's knots and Fresnel correction knots: the material's own limits
// (brdf::MicrofacetModelParams::Validate), so whatever the reader accepts is drawn.
inline constexpr int kMaxTableKnots = brdf::kMaxTableKnots;
inline constexpr int kMaxFresnelKnots = brdf::kMaxFresnelKnots;
static_assert(kMaxTableKnots % 4 == 0 && kMaxFresnelKnots % 4 == 0, "packed four per vec4");

class GpuMaterial {
 public:
  static std::unique_ptr<GpuMaterial> SliceModel(const brdf::SliceModel& model);
  static std::unique_ptr<GpuMaterial> Lambert(const brdf::Rgb& albedo);
  static std::unique_ptr<GpuMaterial> Ggx(const brdf::MicrofacetParams& params);
  static std::unique_ptr<GpuMaterial> Merl(const brdf::MerlTable& table);
  // The ggx, beckmann and microfacet (table) rungs, each with its own shader.
  static std::unique_ptr<GpuMaterial> Microfacet(const brdf::MicrofacetModel& model);
  // The prior rung's table (shaders/rusinkiewicz_table.glsl): its q values in an RGBA32F buffer
  // texture in node order, interpolated in the shader (texelFetch) as on the CPU. Throws
  // brdfrig::Error when the table has more nodes than GL_MAX_TEXTURE_BUFFER_SIZE.
  static std::unique_ptr<GpuMaterial> Table(const brdf::RusinkiewiczTable& table);
  // The gltf kind (shaders/gltf_model.glsl).
  static std::unique_ptr<GpuMaterial> Gltf(const brdf::GltfModel& model);
  // Any BRDF: the kinds above get their own shader; any other model is tabulated into a MERL
  // table (35 MB on the GPU) and drawn with the table shader.
  static std::unique_ptr<GpuMaterial> ForBrdf(const brdf::Brdf& brdf);
  // Every kind of the model ladder (material.json).
  static std::unique_ptr<GpuMaterial> ForMaterial(const brdf::Material& material);
  ~GpuMaterial();

  const GlProgram& program() const { return *program_; }
  // Binds the program, its textures and material uniforms.
  void Bind() const { Bind(*program_); }
  // The material's GLSL (which defines evalMaterial(l, v, n)) linked with another vertex shader
  // and fragment main, e.g. a probe evaluating the BRDF at given directions; Bind(program)
  // then sets the material's parameters on it.
  std::unique_ptr<GlProgram> MakeProgram(const std::string& vertex_file,
                                         const std::string& main_file) const;
  void Bind(const GlProgram& program) const;
  // Slice model only: spline (default) or linear interpolation across theta_in.
  void SetLinearInterpolation(bool linear);

 private:
  friend cv::Mat EvalSliceModelOnGpu(const brdf::SliceModel&, const cv::Mat&, bool);
  GpuMaterial() = default;
  // Compiles the shading program from the material's GLSL files and defines.
  void Build(std::vector<std::string> files, std::vector<std::string> defines);
  std::vector<std::string> files_, defines_;
  std::unique_ptr<GlProgram> program_;
  GLuint texture_ = 0;
  GLenum texture_target_ = 0;
  void UploadSliceBlock();
  GLuint buffer_ = 0;  // slice and microfacet models: their uniform buffer; the table: its texels
  std::vector<float> block_;  // its std140 contents
  int slice_count_ = 0;
  bool linear_ = false;
  brdf::Rgb albedo_ = brdf::Rgb::Zero();
  brdf::MicrofacetParams ggx_;
  brdf::RusinkiewiczGrid table_grid_;
  brdf::GltfParams gltf_;
  enum class Kind {
    kSlice,
    kLambert,
    kGgx,
    kMerl,
    kMicrofacet,
    kTable,
    kGltf
  } kind_ = Kind::kLambert;
};

// Evaluates the slice model's GLSL code at each (theta_in, theta) of `angles` (CV_32FC2) into a
// float target. Returns CV_32FC3 with channels in R, G, B order. Needs a current context.
cv::Mat EvalSliceModelOnGpu(const brdf::SliceModel& model, const cv::Mat& angles,
                            bool linear = false);

}  // namespace brdfrig::render
