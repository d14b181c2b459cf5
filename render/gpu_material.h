// A material on the GPU: its shading program and parameters. The slice model's slices go to a
// small uniform buffer (4 parameters × slices, rgb = channels, plus the knots).
#pragma once

#include <memory>
#include <opencv2/core.hpp>

#include "brdf/analytic.h"
#include "brdf/merl.h"
#include "brdf/slice_model.h"
#include "render/gl_program.h"

namespace brdfrig::render {

inline constexpr int kMaxSlices = 64;
inline constexpr int kMaxLights = 8;

class GpuMaterial {
 public:
  static std::unique_ptr<GpuMaterial> SliceModel(const brdf::SliceModel& model);
  static std::unique_ptr<GpuMaterial> Lambert(const brdf::Rgb& albedo);
  static std::unique_ptr<GpuMaterial> Ggx(const brdf::MicrofacetParams& params);
  static std::unique_ptr<GpuMaterial> Merl(const brdf::MerlTable& table);
  ~GpuMaterial();

  const GlProgram& program() const { return *program_; }
  // Binds the program, its textures and material uniforms.
  void Bind() const;
  // Slice model only: spline (default) or linear interpolation across theta_in.
  void SetLinearInterpolation(bool linear);

 private:
  friend cv::Mat EvalSliceModelOnGpu(const brdf::SliceModel&, const cv::Mat&, bool);
  GpuMaterial() = default;
  std::unique_ptr<GlProgram> program_;
  GLuint texture_ = 0;
  GLenum texture_target_ = 0;
  void UploadSliceBlock();
  GLuint buffer_ = 0;         // slice model: the SliceBlock uniform buffer
  std::vector<float> block_;  // its std140 contents
  int slice_count_ = 0;
  bool linear_ = false;
  brdf::Rgb albedo_ = brdf::Rgb::Zero();
  brdf::MicrofacetParams ggx_;
  enum class Kind { kSlice, kLambert, kGgx, kMerl } kind_ = Kind::kLambert;
};

// Evaluates the slice model's GLSL code at each (theta_in, theta) of `angles` (CV_32FC2) into a
// float target. Returns CV_32FC3 with channels in R, G, B order. Needs a current context.
cv::Mat EvalSliceModelOnGpu(const brdf::SliceModel& model, const cv::Mat& angles,
                            bool linear = false);

}  // namespace brdfrig::render
