// The ladder's microfacet rungs as one model (terms in brdf/microfacet_terms.h):
//
//     f = rho_d / pi + F(theta_d) · D(theta_h) · G1(theta_i) G1(theta_o) / (4 cos_i cos_o)
//
//   ggx         analytic GGX D, Smith G (GGX), Schlick F per channel: 7 numbers
//   beckmann    analytic Beckmann D, Smith G (Beckmann), Schlick F per channel
//   microfacet  data-driven: D a monotone table in theta_h shared by every channel and photo,
//               continued by a fitted GGX tail beyond the observed theta_h; Smith G (GGX form,
//               its own roughness); Schlick F per channel times an optional correction in
//               theta_d shared by the channels
//
// D of the table rung is normalized on construction (projected area 1), so f0 is the
// specular reflectance at normal incidence and energy follows from f0 and rho_d.
#pragma once

#include <string>
#include <vector>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

enum class Distribution { kGgx, kBeckmann, kTable };

// The most table and Fresnel correction knots a model may have: what the renderer holds
// (render/gpu_material.h), so a file the reader accepts is one every writer can draw.
inline constexpr int kMaxTableKnots = 256;
inline constexpr int kMaxFresnelKnots = 64;

const char* DistributionName(Distribution d);  // "ggx", "beckmann", "microfacet"

struct MicrofacetModelParams {
  Distribution distribution = Distribution::kGgx;
  Rgb diffuse = Rgb::Zero();          // rho_d, Lambertian albedo, in [0, 1]
  Rgb f0 = Rgb::Constant(0.04);       // Schlick reflectance at normal incidence, in [0, 1]
  double alpha = 0.2;                 // GGX/Beckmann roughness; the table's tail roughness
  std::vector<double> fresnel_knots;  // ln F multiplier at equal theta_d steps; empty = none
  // Table rung only:
  std::vector<double> log_d;     // ln D at the knots (>= 2, non-increasing)
  double max_theta_h = 0;        // theta_h of the last knot (radians, (0, pi/2])
  double shadowing_alpha = 0.2;  // roughness of Smith's G (GGX form)

  // Throws brdfrig::Error naming the field, its value and the rule.
  void Validate() const;
};

class MicrofacetModel : public Brdf {
 public:
  explicit MicrofacetModel(MicrofacetModelParams params);  // validates

  Rgb Eval(const Vec3& l, const Vec3& v, const Vec3& n) const override;
  std::string Name() const override;

  // As stored (the table as given, before normalization).
  const MicrofacetModelParams& params() const { return params_; }
  // ln D of the table after normalization (what Eval and the shader use); empty for analytic D.
  const std::vector<double>& normalized_log_d() const { return normalized_log_d_; }
  // The table's projected-area integral before normalization (1 for analytic D).
  double table_normalization() const { return normalization_; }

  // D(theta_h) as evaluated (normalized), and Smith's G1 for a direction at cos_t.
  double D(double cos_h) const;
  double G1(double cos_t) const;

 private:
  MicrofacetModelParams params_;
  std::vector<double> normalized_log_d_;
  double normalization_ = 1;
};

}  // namespace brdfrig::brdf
