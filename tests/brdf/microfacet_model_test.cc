#include "brdf/microfacet_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "brdf/analytic.h"
#include "brdf/metrics.h"
#include "brdf/microfacet_terms.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

using ::testing::HasSubstr;

Vec3 Direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// A table sampled from GGX at its own knots, with a GGX tail of the same roughness.
MicrofacetModelParams GgxTable(double alpha, double max_theta_h, int knots) {
  MicrofacetModelParams p;
  p.distribution = Distribution::kTable;
  p.f0 = {0.9, 0.5, 0.2};
  p.diffuse = {0.05, 0.1, 0.2};
  p.alpha = alpha;
  p.shadowing_alpha = alpha;
  p.max_theta_h = max_theta_h;
  for (int k = 0; k < knots; ++k) {
    p.log_d.push_back(std::log(
        microfacet::GgxD(std::cos(microfacet::TableKnotThetaH(k, knots, max_theta_h)), alpha)));
  }
  return p;
}

TEST(MicrofacetModelTest, GgxRungEqualsTheAnalyticGgxReference) {
  MicrofacetParams reference{{0.1, 0.2, 0.3}, {0.9, 0.6, 0.35}, 0.12};
  MicrofacetModelParams p;
  p.distribution = Distribution::kGgx;
  p.diffuse = reference.diffuse;
  p.f0 = reference.f0;
  p.alpha = reference.alpha;
  const MicrofacetModel model(p);
  const Ggx ggx(reference);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 500; ++i) {
    const Vec3 l = Direction(u(rng) * 1.55, u(rng) * 6.28),
               v = Direction(u(rng) * 1.55, u(rng) * 6.28);
    const Rgb a = model.Eval(l, v, Vec3::UnitZ()), b = ggx.Eval(l, v, Vec3::UnitZ());
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-12 * std::max(1.0, b[c]));
  }
}

TEST(MicrofacetModelTest, TableOfGgxReproducesGgxAndIsAlreadyNormalized) {
  for (double alpha : {0.05, 0.2, 0.5}) {
    const MicrofacetModel table(GgxTable(alpha, 0.9, 32));
    EXPECT_NEAR(table.table_normalization(), 1.0, 5e-3) << alpha;
    MicrofacetModelParams p = GgxTable(alpha, 0.9, 32);
    p.distribution = Distribution::kGgx;
    p.log_d.clear();
    const MicrofacetModel ggx(p);
    for (double theta_h : {0.0, 0.01, 0.1, 0.3, 0.8, 1.0, 1.4}) {
      const double c = std::cos(theta_h);
      EXPECT_NEAR(table.D(c) / ggx.D(c), 1.0, 0.03) << "alpha " << alpha << " theta_h " << theta_h;
    }
  }
}

TEST(MicrofacetModelTest, TableScaleDoesNotMatterBecauseDIsNormalized) {
  MicrofacetModelParams p = GgxTable(0.1, 0.7, 16);
  const MicrofacetModel a(p);
  for (double& x : p.log_d) x += 3.0;
  const MicrofacetModel b(p);
  const Vec3 l = Direction(0.4, 0), v = Direction(0.45, 3.1);
  EXPECT_NEAR(a.Eval(l, v, Vec3::UnitZ())[0], b.Eval(l, v, Vec3::UnitZ())[0], 1e-9);
}

TEST(MicrofacetModelTest, EveryRungIsReciprocalAndConservesEnergy) {
  for (Distribution d : {Distribution::kGgx, Distribution::kBeckmann, Distribution::kTable}) {
    MicrofacetModelParams p = GgxTable(0.3, 1.0, 24);
    p.f0 = Rgb::Ones();
    p.diffuse = Rgb::Zero();
    p.fresnel_knots = {0, -0.05, -0.1};  // F <= 1 everywhere
    if (d != Distribution::kTable) p.log_d.clear();
    p.distribution = d;
    const MicrofacetModel model(p);
    EXPECT_LT(ReciprocityError(model), 1e-9) << DistributionName(d);
    for (double theta_in : {0.0, 0.5, 1.0, 1.3, 1.5}) {
      const Rgb albedo = DirectionalAlbedo(model, theta_in, {256, 256});
      EXPECT_LE(albedo.maxCoeff(), 1.0) << DistributionName(d) << " at " << theta_in;
      EXPECT_GT(albedo.minCoeff(), 0.3) << DistributionName(d) << " at " << theta_in;
    }
  }
}

TEST(MicrofacetModelTest, DiffuseOnlyIsAWhiteFurnaceOfItsAlbedo) {
  // The Lambertian term adds exactly its albedo on top of the specular term.
  MicrofacetModelParams p;
  p.distribution = Distribution::kGgx;
  p.f0 = Rgb::Constant(0.04);
  const Rgb specular_only = DirectionalAlbedo(MicrofacetModel(p), 0.7);
  p.diffuse = {0.2, 0.5, 0.8};
  const Rgb albedo = DirectionalAlbedo(MicrofacetModel(p), 0.7);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(albedo[c] - specular_only[c], p.diffuse[c], 2e-3);
}

TEST(MicrofacetModelTest, FiniteAtGrazingAndAtTheExactMirrorDirection) {
  for (Distribution d : {Distribution::kGgx, Distribution::kBeckmann, Distribution::kTable}) {
    MicrofacetModelParams p = GgxTable(0.05, 0.5, 32);
    if (d != Distribution::kTable) p.log_d.clear();
    p.distribution = d;
    const MicrofacetModel model(p);
    const Vec3 n = Vec3::UnitZ();
    for (double theta : {0.0, 1.0, M_PI / 2 - 1e-9}) {
      const Vec3 l = Direction(theta, 0), mirror = Direction(theta, M_PI);
      EXPECT_TRUE(model.Eval(l, mirror, n).isFinite().all()) << DistributionName(d) << theta;
      EXPECT_TRUE(model.Eval(l, l, n).isFinite().all()) << DistributionName(d) << theta;
    }
  }
}

TEST(MicrofacetModelTest, InvalidParametersNameFieldValueAndRule) {
  MicrofacetModelParams p = GgxTable(0.1, 0.7, 8);
  p.log_d[4] = p.log_d[3] + 1;
  try {
    MicrofacetModel m(p);
    FAIL() << "accepted a rising table";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("log_d[4] = "));
    EXPECT_THAT(e.what(), HasSubstr("must be <= log_d[3] (D is monotone)"));
  }
  p = GgxTable(0.1, 0.7, 8);
  p.alpha = 0;
  EXPECT_THROW(MicrofacetModel{p}, Error);
  p = GgxTable(0.1, 0.7, 8);
  p.diffuse[2] = std::nan("");
  EXPECT_THROW(MicrofacetModel{p}, Error);
}

}  // namespace
}  // namespace brdfrig::brdf
