#include "brdf/analytic.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "brdf/metrics.h"
#include "brdf/slice_model.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

const Vec3 kN = Vec3::UnitZ();

std::vector<std::shared_ptr<Brdf>> AllAnalytic() {
  MicrofacetParams glossy{Rgb(0.2, 0.3, 0.4), Rgb(0.04, 0.05, 0.06), 0.25};
  return {std::make_shared<Lambert>(Rgb(0.8, 0.5, 0.2)), std::make_shared<Ggx>(glossy),
          std::make_shared<CookTorrance>(glossy),
          std::make_shared<Ward>(WardParams{Rgb(0.2, 0.3, 0.4), Rgb(0.05, 0.05, 0.05), 0.25}),
          std::make_shared<BlinnPhong>(
              BlinnPhongParams{Rgb(0.2, 0.3, 0.4), Rgb(0.05, 0.05, 0.05), 50})};
}

TEST(AnalyticBrdfTest, EveryModelIsReciprocal) {
  for (const auto& brdf : AllAnalytic()) {
    EXPECT_LT(ReciprocityError(*brdf, {16, 32}), 1e-10) << brdf->Name();
  }
}

TEST(AnalyticBrdfTest, EveryModelIsNonNegativeAndZeroBelowTheHorizon) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (const auto& brdf : AllAnalytic()) {
    for (int i = 0; i < 2000; ++i) {
      const Vec3 l = Vec3(g(rng), g(rng), g(rng)).normalized();
      const Vec3 v = Vec3(g(rng), g(rng), g(rng)).normalized();
      const Rgb f = brdf->Eval(l, v, kN);
      ASSERT_TRUE(f.isFinite().all()) << brdf->Name();
      ASSERT_GE(f.minCoeff(), 0) << brdf->Name();
      if (l.z() <= 0 || v.z() <= 0) {
        ASSERT_EQ(f.maxCoeff(), 0) << brdf->Name();
      }
    }
  }
}

TEST(AnalyticBrdfTest, DirectionalAlbedoNeverExceedsOne) {
  // A white, shiny version of each model is the hardest case for energy conservation.
  MicrofacetParams white{Rgb::Zero(), Rgb::Ones(), 0.3};
  std::vector<std::shared_ptr<Brdf>> models = {
      std::make_shared<Ggx>(white), std::make_shared<CookTorrance>(white),
      std::make_shared<Ward>(WardParams{Rgb::Zero(), Rgb::Ones(), 0.3})};
  for (const auto& brdf : models) {
    for (double theta_in : {0.0, 0.5, 1.0, 1.3}) {
      const Rgb a = DirectionalAlbedo(*brdf, theta_in, {128, 256});
      EXPECT_LE(a.maxCoeff(), 1.0 + 2e-3) << brdf->Name() << " at " << theta_in;
      EXPECT_GT(a.minCoeff(), 0.3) << brdf->Name() << " at " << theta_in;
    }
  }
}

TEST(AnalyticBrdfTest, WhiteFurnaceLambertReturnsItsAlbedo) {
  const Lambert white(Rgb::Ones());
  for (double theta_in : {0.0, 0.7, 1.5}) {
    EXPECT_NEAR(DirectionalAlbedo(white, theta_in).maxCoeff(), 1.0, 1e-12);
    EXPECT_NEAR(DirectionalAlbedo(white, theta_in).minCoeff(), 1.0, 1e-12);
  }
}

TEST(AnalyticBrdfTest, ClosedFormValuesAtNormalIncidence) {
  const double a = 0.3;
  const MicrofacetParams p{Rgb::Zero(), Rgb::Constant(0.05), a};
  // D(n) = 1/(pi a^2), G = 1, F = f0: f = f0 / (4 pi a^2) for both GGX and Beckmann.
  EXPECT_NEAR(Ggx(p).Eval(kN, kN, kN)[0], 0.05 / (4 * M_PI * a * a), 1e-12);
  EXPECT_NEAR(CookTorrance(p).Eval(kN, kN, kN)[0], 0.05 / (4 * M_PI * a * a), 1e-12);
  EXPECT_NEAR(Ward({Rgb::Zero(), Rgb::Constant(0.05), a}).Eval(kN, kN, kN)[0],
              0.05 / (4 * M_PI * a * a), 1e-12);
  EXPECT_NEAR(BlinnPhong({Rgb::Zero(), Rgb::Constant(0.05), 20}).Eval(kN, kN, kN)[0],
              0.05 * 28 / (8 * M_PI), 1e-12);
  EXPECT_NEAR(Lambert(Rgb::Constant(0.5)).Eval(kN, kN, kN)[0], 0.5 / M_PI, 1e-15);
}

TEST(AnalyticBrdfTest, InvalidParametersAreRejected) {
  EXPECT_THROW(Lambert(Rgb(1.2, 0, 0)), Error);
  EXPECT_THROW(Ggx({Rgb::Zero(), Rgb::Constant(0.04), 0.0}), Error);
  EXPECT_THROW(Ward({Rgb::Zero(), Rgb::Constant(NAN), 0.1}), Error);
}

TEST(MetricsTest, LogErrorIsZeroForIdenticalAndGrowsWithDifference) {
  const Ggx a({Rgb::Constant(0.2), Rgb::Constant(0.04), 0.2});
  const Ggx b({Rgb::Constant(0.2), Rgb::Constant(0.04), 0.3});
  const Ggx c({Rgb::Constant(0.2), Rgb::Constant(0.04), 0.5});
  EXPECT_EQ(LogCosineError(a, a), 0);
  EXPECT_GT(LogCosineError(a, b), 0);
  EXPECT_GT(LogCosineError(a, c), LogCosineError(a, b));
  EXPECT_NEAR(LogCosineError(a, b), LogCosineError(b, a), 1e-15);
}

TEST(MetricsTest, InvalidOptionsAreRejected) {
  const Lambert a(Rgb::Ones());
  EXPECT_THROW(DirectionalAlbedo(a, 0, {1, 8}), OptionsError);
}

}  // namespace
}  // namespace brdfrig::brdf
