// The GLSL microfacet rungs (shaders/microfacet_model.glsl) against the CPU reference
// (brdf::MicrofacetModel::Eval, double) on a dense grid of light and view directions: every
// incidence and exit angle up to 89.9°, relative azimuths 0…180°, the exact mirror direction and
// its close neighbourhood (where sharp lobes live), and directions a hair above the horizon.
// Runs on llvmpipe in CI.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "brdf/microfacet_model.h"
#include "brdf/microfacet_terms.h"
#include "render/gl_context.h"
#include "render/gpu_material.h"
#include "render/material_probe.h"
#include "tests/render/direction_grid.h"

namespace brdfrig::render {
namespace {

using testing::Agreement;
using testing::CompareOnGrid;
using testing::DirectionGrid;
using testing::MakeGrid;

constexpr double kDeg = M_PI / 180;

// float32 evaluation of a model whose values span ~10 decades: relative error where the value
// is meaningful, absolute below kFloor (1/sr; a dark diffuse is 0.01/pi ≈ 3e-3).
constexpr double kTolerance = 1e-4;
constexpr double kFloor = 1e-4;

// |gpu − cpu| / max(|cpu|, kFloor) over the grid rotated to `normal`.
Agreement Compare(const brdf::MicrofacetModel& model, const DirectionGrid& grid,
                  const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
  const std::unique_ptr<GpuMaterial> material = GpuMaterial::Microfacet(model);
  return CompareOnGrid(*material, model, grid, normal,
                       [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return kFloor; });
}

double AngleDeg(const Eigen::Vector3d& a) { return std::acos(std::clamp(a.z(), -1.0, 1.0)) / kDeg; }

class MicrofacetAgreementTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = CreateHeadlessContext().release();
    grid_ = new DirectionGrid(MakeGrid(true));
    // Rotated, a cosine of 1e-6 falls below float's resolution and the float and double sides
    // of the horizon cut differ: the tilted grid stops at 89.9°.
    tilted_grid_ = new DirectionGrid(MakeGrid(false));
  }
  static void TearDownTestSuite() {
    delete grid_;
    delete tilted_grid_;
    delete context_;
  }
  // Compares, prints and records the worst error under `name`.
  static double Check(const std::string& name, const brdf::MicrofacetModel& model,
                      const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
    const Agreement a = Compare(model, normal.z() == 1 ? *grid_ : *tilted_grid_, normal);
    RecordProperty("max_relative_" + name, std::to_string(a.max_relative));
    std::printf("%s: max relative error %.3g over %d values (at theta_in %.4f°, theta_out %.4f°)\n",
                name.c_str(), a.max_relative, a.checked, AngleDeg(a.light_at), AngleDeg(a.view_at));
    return a.max_relative;
  }
  static GlContext* context_;
  static DirectionGrid* grid_;
  static DirectionGrid* tilted_grid_;
};
GlContext* MicrofacetAgreementTest::context_ = nullptr;
DirectionGrid* MicrofacetAgreementTest::grid_ = nullptr;
DirectionGrid* MicrofacetAgreementTest::tilted_grid_ = nullptr;

brdf::MicrofacetModelParams Analytic(brdf::Distribution d, double alpha) {
  brdf::MicrofacetModelParams p;
  p.distribution = d;
  p.alpha = alpha;
  p.diffuse = brdf::Rgb(0.1, 0.05, 0.03);
  p.f0 = brdf::Rgb(0.9, 0.6, 0.35);
  return p;
}

// A table shaped like a broad peak plus a narrow one (not any analytic D), with a GGX tail.
brdf::MicrofacetModelParams Table(int knots, double max_theta_h) {
  brdf::MicrofacetModelParams p;
  p.distribution = brdf::Distribution::kTable;
  p.alpha = 0.25;
  p.shadowing_alpha = 0.15;
  p.max_theta_h = max_theta_h;
  p.diffuse = brdf::Rgb(0.2, 0.1, 0.05);
  p.f0 = brdf::Rgb(0.04, 0.05, 0.06);
  p.fresnel_knots = {0, -0.05, 0.1, -0.2, 0.3};
  for (int k = 0; k < knots; ++k) {
    const double t = brdf::microfacet::TableKnotThetaH(k, knots, max_theta_h);
    p.log_d.push_back(std::log(50 * std::exp(-t * t / 0.002) + 2 * std::exp(-t * t / 0.1) + 1e-3));
  }
  return p;
}

TEST_F(MicrofacetAgreementTest, GgxAgreesToFloatTolerance) {
  for (double alpha : {0.02, 0.1, 0.4, 1.0}) {
    const brdf::MicrofacetModel model(Analytic(brdf::Distribution::kGgx, alpha));
    EXPECT_LT(Check("ggx_alpha_" + std::to_string(alpha), model), kTolerance);
  }
}

TEST_F(MicrofacetAgreementTest, BeckmannAgreesToFloatTolerance) {
  for (double alpha : {0.02, 0.1, 0.4, 1.0}) {
    const brdf::MicrofacetModel model(Analytic(brdf::Distribution::kBeckmann, alpha));
    EXPECT_LT(Check("beckmann_alpha_" + std::to_string(alpha), model), kTolerance);
  }
}

TEST_F(MicrofacetAgreementTest, TableWithTailAndFresnelKnotsAgreesToFloatTolerance) {
  const brdf::MicrofacetModel model(Table(32, 0.6));
  EXPECT_LT(Check("microfacet_32_knots", model), kTolerance);
}

TEST_F(MicrofacetAgreementTest, TableOverTheWholeRangeWithMostKnotsAgrees) {
  brdf::MicrofacetModelParams p = Table(kMaxTableKnots, M_PI / 2);
  p.fresnel_knots = {0.1};
  EXPECT_LT(Check("microfacet_256_knots_no_tail", brdf::MicrofacetModel(p)), kTolerance);
  p = Table(2, 0.05);
  p.fresnel_knots.clear();
  EXPECT_LT(Check("microfacet_2_knots", brdf::MicrofacetModel(p)), kTolerance);
}

TEST_F(MicrofacetAgreementTest, EveryKindAgreesForATiltedNormal) {
  const Eigen::Vector3d normal = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  EXPECT_LT(
      Check("ggx_tilted", brdf::MicrofacetModel(Analytic(brdf::Distribution::kGgx, 0.1)), normal),
      kTolerance);
  EXPECT_LT(Check("beckmann_tilted",
                  brdf::MicrofacetModel(Analytic(brdf::Distribution::kBeckmann, 0.1)), normal),
            kTolerance);
  EXPECT_LT(Check("microfacet_tilted", brdf::MicrofacetModel(Table(32, 0.6)), normal), kTolerance);
}

TEST_F(MicrofacetAgreementTest, ExtremeRoughnessStaysFinite) {
  // alpha at the limits Validate allows: a 3e7/sr mirror spike and a nearly flat lobe.
  for (double alpha : {1e-4, 4.0}) {
    for (brdf::Distribution d : {brdf::Distribution::kGgx, brdf::Distribution::kBeckmann}) {
      const brdf::MicrofacetModel model(Analytic(d, alpha));
      EXPECT_LT(
          Check(std::string(brdf::DistributionName(d)) + "_alpha_" + std::to_string(alpha), model),
          1e-3);
    }
  }
}

}  // namespace
}  // namespace brdfrig::render
