// Every kind of the model ladder reaches the GPU with its own shader (GpuMaterial::ForMaterial
// and ForBrdf, used by the renderer, viewer, `brdfrig render` and evaluation): the GPU values
// match the CPU model closely, which a MERL table (the fallback for unknown BRDFs, nearest bin)
// would not. The prior's Rusinkiewicz table gets shaders/rusinkiewicz_table.glsl.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "brdf/analytic.h"
#include "brdf/material_file.h"
#include "brdf/microfacet_terms.h"
#include "render/gl_context.h"
#include "render/gpu_material.h"
#include "render/material_probe.h"

namespace brdfrig::render {
namespace {

constexpr double kDeg = M_PI / 180;

brdf::Material MakeMaterial(brdf::ModelKind kind) {
  brdf::Material m;
  m.kind = kind;
  if (brdf::IsSliceKind(kind)) {
    for (int k = 0; k < 4; ++k) {
      brdf::Slice s;
      s.theta_in = (15 + 20 * k) * kDeg;
      for (auto& c : s.channel) c = {5.0 + k, 0.05, 0.03, 0.08};
      m.slices.push_back(s);
    }
    return m;
  }
  if (kind == brdf::ModelKind::kPrior) {
    // A table of a GGX lobe on the default grid, as the prior rung writes it.
    m.table = brdf::TabulateBrdf(
        brdf::Ggx({brdf::Rgb(0.2, 0.1, 0.05), brdf::Rgb(0.5, 0.4, 0.3), 0.15}), m.table_grid);
    return m;
  }
  if (kind == brdf::ModelKind::kGltf) {
    // Half metal, a coloured dielectric specular: every term of the glTF BRDF counts.
    brdf::GltfParams g;
    g.base_color = brdf::Rgb(0.6, 0.3, 0.1);
    g.metallic = 0.5;
    g.roughness = 0.4;
    g.ior = 1.7;
    g.specular = 0.8;
    g.specular_color = brdf::Rgb(1.0, 0.7, 0.5);
    m.gltf = g;
    return m;
  }
  brdf::MicrofacetModelParams& p = m.microfacet;
  p.diffuse = brdf::Rgb(0.2, 0.1, 0.05);
  p.f0 = brdf::Rgb(0.5, 0.4, 0.3);
  p.alpha = 0.15;
  if (kind == brdf::ModelKind::kGgx) p.distribution = brdf::Distribution::kGgx;
  if (kind == brdf::ModelKind::kBeckmann) p.distribution = brdf::Distribution::kBeckmann;
  if (kind == brdf::ModelKind::kMicrofacet) {
    p.distribution = brdf::Distribution::kTable;
    p.max_theta_h = 0.5;
    p.fresnel_knots = {0, 0.1, -0.1};
    for (int k = 0; k < 16; ++k) {
      p.log_d.push_back(brdf::microfacet::LogGgxD(
          std::cos(brdf::microfacet::TableKnotThetaH(k, 16, p.max_theta_h)), 0.15));
    }
  }
  return m;
}

// Max relative difference (floor 1e-3/sr) between the GPU material and the CPU model over a
// grid of light and view directions up to 85°.
double MaxRelativeDifference(const GpuMaterial& gpu, const brdf::Brdf& cpu) {
  const int n = 24;
  cv::Mat light(n * n, n, CV_32FC3), view(n * n, n, CV_32FC3);
  for (int i = 0; i < n * n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double ti = (i / n) * 85.0 / (n - 1) * kDeg, to = (i % n) * 85.0 / (n - 1) * kDeg;
      const double phi = M_PI * j / (n - 1);
      light.at<cv::Vec3f>(i, j) = cv::Vec3f(std::sin(ti), 0, std::cos(ti));
      view.at<cv::Vec3f>(i, j) =
          cv::Vec3f(-std::sin(to) * std::cos(phi), std::sin(to) * std::sin(phi), std::cos(to));
    }
  }
  const cv::Mat values = EvalMaterialOnGpu(gpu, light, view, Eigen::Vector3f::UnitZ());
  double worst = 0;
  for (int i = 0; i < light.rows; ++i) {
    for (int j = 0; j < light.cols; ++j) {
      const cv::Vec3f l = light.at<cv::Vec3f>(i, j), v = view.at<cv::Vec3f>(i, j);
      const brdf::Rgb f = cpu.Eval({l[0], l[1], l[2]}, {v[0], v[1], v[2]}, brdf::Vec3::UnitZ());
      const cv::Vec3f g = values.at<cv::Vec3f>(i, j);
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(g[c] - f[c]) / std::max(std::abs(f[c]), 1e-3));
      }
    }
  }
  return worst;
}

TEST(GpuMaterialDispatchTest, EveryLadderKindUsesItsOwnShader) {
  const auto context = CreateHeadlessContext();
  for (brdf::ModelKind kind : brdf::kAllModelKinds) {
    SCOPED_TRACE(brdf::ModelKindName(kind));
    const brdf::Material material = MakeMaterial(kind);
    const std::shared_ptr<const brdf::Brdf> model = material.Model();
    // The slice model works in angles computed from the directions: float angles near the
    // mirror direction carry ~1e-4 relative error there; the microfacet and table shaders ~1e-5
    // (the prior's table through MERL bins would be off by percent).
    const double tolerance = brdf::IsSliceKind(kind) ? 2e-3 : 1e-4;
    EXPECT_LT(MaxRelativeDifference(*GpuMaterial::ForMaterial(material), *model), tolerance);
    EXPECT_LT(MaxRelativeDifference(*GpuMaterial::ForBrdf(*model), *model), tolerance);
  }
}

}  // namespace
}  // namespace brdfrig::render
