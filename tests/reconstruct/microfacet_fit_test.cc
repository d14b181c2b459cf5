// The microfacet fits recover what synthetic photos of a known microfacet BRDF were made from.
#include "reconstruct/microfacet_fit.h"

#include <gtest/gtest.h>

#include "brdf/metrics.h"
#include "brdf/microfacet_terms.h"
#include "reconstruct/energy.h"
#include "tests/reconstruct/direction_patches.h"

namespace brdfrig::reconstruct {
namespace {

using testing::AllPatches;
using testing::DesignedPatches;

brdf::MicrofacetModelParams Analytic(brdf::Distribution d, double alpha) {
  brdf::MicrofacetModelParams p;
  p.distribution = d;
  p.alpha = alpha;
  p.diffuse = brdf::Rgb(0.30, 0.15, 0.05);
  p.f0 = brdf::Rgb(0.06, 0.05, 0.04);
  return p;
}

void ExpectRecovered(const brdf::MicrofacetModelParams& want, const MicrofacetFit& got) {
  EXPECT_NEAR(got.params.alpha, want.alpha, 0.03 * want.alpha);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(got.params.diffuse[c], want.diffuse[c], 0.03 * want.diffuse[c]) << c;
    EXPECT_NEAR(got.params.f0[c], want.f0[c], 0.05 * want.f0[c]) << c;
  }
}

TEST(MicrofacetFitTest, GgxFitRecoversAlphaF0AndDiffuseFromSixPatches) {
  const auto truth = Analytic(brdf::Distribution::kGgx, 0.12);
  const auto samples = AllPatches(brdf::MicrofacetModel(truth), DesignedPatches());
  const MicrofacetFit fit = FitAnalyticMicrofacet(samples, brdf::Distribution::kGgx, {});
  std::cout << fit.diagnostics.dump() << "\n";
  ExpectRecovered(truth, fit);
  EXPECT_TRUE(fit.diffuse_observed[0] && fit.diffuse_observed[1] && fit.diffuse_observed[2]);
}

TEST(MicrofacetFitTest, BeckmannFitRecoversAlphaF0AndDiffuseFromSixPatches) {
  const auto truth = Analytic(brdf::Distribution::kBeckmann, 0.2);
  const auto samples = AllPatches(brdf::MicrofacetModel(truth), DesignedPatches());
  const MicrofacetFit fit = FitAnalyticMicrofacet(samples, brdf::Distribution::kBeckmann, {});
  std::cout << fit.diagnostics.dump() << "\n";
  ExpectRecovered(truth, fit);
}

// A table D tabulated from `d` (any shape) on 32 knots over [0, max_theta_h].
template <typename F>
brdf::MicrofacetModelParams TableTruth(F d, double max_theta_h) {
  brdf::MicrofacetModelParams p;
  p.distribution = brdf::Distribution::kTable;
  p.max_theta_h = max_theta_h;
  p.alpha = 0.3;
  p.shadowing_alpha = 0.1;
  p.diffuse = brdf::Rgb(0.10, 0.05, 0.02);
  p.f0 = brdf::Rgb(0.6, 0.45, 0.3);  // albedo < 1 with the diffuse term
  for (int k = 0; k < 32; ++k) {
    p.log_d.push_back(std::log(d(brdf::microfacet::TableKnotThetaH(k, 32, max_theta_h))));
  }
  return p;
}

void ExpectTableRecovered(const brdf::MicrofacetModelParams& truth_params, double tolerance) {
  const brdf::MicrofacetModel truth(truth_params);
  const auto samples = AllPatches(truth, DesignedPatches());
  const MicrofacetFit ggx = FitAnalyticMicrofacet(samples, brdf::Distribution::kGgx, {});
  const MicrofacetFit fit = FitTableMicrofacet(samples, ggx.params, {});
  std::cout << "ggx residual " << ggx.residual << ", table " << fit.diagnostics.dump() << "\n";
  const brdf::MicrofacetModel got(fit.params);
  // Where photos see theta_h (each patch spans a few degrees about its centre).
  for (double deg : {0.0, 1.0, 2.0, 4.0, 10.0, 25.0, 40.0}) {
    const double c = std::cos(deg * M_PI / 180);
    EXPECT_NEAR(std::log(got.D(c)), std::log(truth.D(c)), tolerance) << "theta_h " << deg;
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(fit.params.f0[c], truth_params.f0[c], 0.1 * truth_params.f0[c]) << c;
    EXPECT_NEAR(fit.params.diffuse[c], truth_params.diffuse[c], 0.1 * truth_params.diffuse[c]);
  }
  EXPECT_LT(fit.residual, 0.5 * ggx.residual + 0.02);
}

TEST(MicrofacetFitTest, TableFitRecoversAGgxShapedD) {
  ExpectTableRecovered(
      TableTruth([](double t) { return brdf::microfacet::GgxD(std::cos(t), 0.08); }, 0.9), 0.15);
}

TEST(MicrofacetFitTest, TableFitRecoversACorePlusHazeD) {
  ExpectTableRecovered(TableTruth(
                           [](double t) {
                             return 0.7 * brdf::microfacet::GgxD(std::cos(t), 0.04) +
                                    0.3 * brdf::microfacet::GgxD(std::cos(t), 0.3);
                           },
                           0.9),
                       0.2);
}

}  // namespace
}  // namespace brdfrig::reconstruct
