// The GLSL Rusinkiewicz table (shaders/rusinkiewicz_table.glsl, the prior rung's shader) against
// the CPU reference (brdf::RusinkiewiczTable::Eval, double) on a dense grid of light and view
// directions: every incidence and exit angle up to 89.9°, relative azimuths 0…180°, the exact
// mirror direction and its close neighbourhood, directions a hair above the horizon, and the
// grid rotated to a tilted normal. The tables are brdf::TabulateBrdf of an analytic GGX and of
// a measured material (nbrdf "steel"). Runs on llvmpipe in CI.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "brdf/analytic.h"
#include "brdf/nbrdf_library.h"
#include "brdf/rusinkiewicz_table.h"
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

// float32 evaluation: the error is |gpu − cpu| / max(|cpu|, kFloor, eps / c), relative where
// the value is meaningful and absolute below the floor: kFloor as in the microfacet test, and
// eps / c, the level the mapping q = ln(f·c + eps) itself resolves (q is stored as float32: its
// rounding, 2^-24 |q|, is an error of exp(q) = f·c + eps, not of f, and with eps = 1e-2 and
// f·c = 4e-5 it alone is 2e-4 of f). The angles in float move the continuous index by ~1e-6 of
// a cell and q changes by up to a few units per cell on a sharp lobe: ~1e-5 in all.
constexpr double kTolerance = 1e-4;
constexpr double kFloor = 1e-4;

// |gpu − cpu| / max(|cpu|, kFloor, eps / c) over the grid rotated to `normal`, pairs with θh
// below `min_theta_h` left out.
Agreement Compare(const GpuMaterial& material, const brdf::RusinkiewiczTable& table,
                  const DirectionGrid& grid, const Eigen::Vector3d& normal, double min_theta_h) {
  const brdf::RusinkiewiczGrid& tg = table.grid();
  return CompareOnGrid(
      material, table, grid, normal,
      [&](const Eigen::Vector3d& l, const Eigen::Vector3d& v) {
        const double cosines = std::max(l.z(), tg.cos_floor) * std::max(v.z(), tg.cos_floor);
        return std::max(kFloor, tg.epsilon / cosines);
      },
      [&](const Eigen::Vector3d& l, const Eigen::Vector3d& v) {
        return min_theta_h <= 0 || brdf::ToHalfDiffAngles(l, v).theta_h >= min_theta_h;
      });
}

double AngleDeg(const Eigen::Vector3d& a) { return std::acos(std::clamp(a.z(), -1.0, 1.0)) / kDeg; }

class TableAgreementTest : public ::testing::Test {
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
  // Pairs whose theta_h is below min_theta_h are left out.
  static double Check(const std::string& name, const brdf::RusinkiewiczTable& table,
                      const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ(),
                      double min_theta_h = 0) {
    const std::unique_ptr<GpuMaterial> material = GpuMaterial::Table(table);
    const Agreement a =
        Compare(*material, table, normal.z() == 1 ? *grid_ : *tilted_grid_, normal, min_theta_h);
    RecordProperty("max_relative_" + name, std::to_string(a.max_relative));
    std::printf("%s: max relative error %.3g over %d values (at theta_in %.4f°, theta_out %.4f°)\n",
                name.c_str(), a.max_relative, a.checked, AngleDeg(a.light_at), AngleDeg(a.view_at));
    return a.max_relative;
  }
  static GlContext* context_;
  static DirectionGrid* grid_;
  static DirectionGrid* tilted_grid_;
};
GlContext* TableAgreementTest::context_ = nullptr;
DirectionGrid* TableAgreementTest::grid_ = nullptr;
DirectionGrid* TableAgreementTest::tilted_grid_ = nullptr;

brdf::RusinkiewiczTable TableOf(const brdf::Brdf& brdf, const brdf::RusinkiewiczGrid& grid) {
  return brdf::RusinkiewiczTable(grid, brdf::TabulateBrdf(brdf, grid));
}

brdf::Ggx AnalyticGgx(double alpha) {
  return brdf::Ggx({brdf::Rgb(0.1, 0.05, 0.03), brdf::Rgb(0.9, 0.6, 0.35), alpha});
}

TEST_F(TableAgreementTest, GgxTableAgreesToFloatTolerance) {
  const brdf::RusinkiewiczGrid grid;  // the prior's default 64 x 32 x 8
  for (double alpha : {0.05, 0.2, 0.6}) {
    EXPECT_LT(Check("ggx_alpha_" + std::to_string(alpha), TableOf(AnalyticGgx(alpha), grid)),
              kTolerance);
  }
}

TEST_F(TableAgreementTest, MeasuredSteelTableAgreesToFloatTolerance) {
  const brdf::NeuralBrdf steel = brdf::ReadNbrdfMaterial("steel");
  EXPECT_LT(Check("steel", TableOf(steel, brdf::RusinkiewiczGrid{})), kTolerance);
}

TEST_F(TableAgreementTest, OtherGridsAndMappingsAgree) {
  // A fine grid, the smallest one (every lookup at the table's edges), and non-default epsilons
  // and cosine floors (floor 1: c = 1 everywhere).
  brdf::RusinkiewiczGrid fine{128, 64, 16};
  EXPECT_LT(Check("ggx_128x64x16", TableOf(AnalyticGgx(0.1), fine)), kTolerance);
  brdf::RusinkiewiczGrid smallest{2, 2, 2};
  EXPECT_LT(Check("ggx_2x2x2", TableOf(AnalyticGgx(0.3), smallest)), kTolerance);
  EXPECT_LT(Check("ggx_16x8x3_eps_0.5_floor_1", TableOf(AnalyticGgx(0.3), {16, 8, 3, 0.5, 1.0})),
            kTolerance);
  brdf::RusinkiewiczGrid mapping{48, 24, 5, 1e-2, 0.2};
  EXPECT_LT(
      Check("steel_48x24x5_eps_1e-2_floor_0.2", TableOf(brdf::ReadNbrdfMaterial("steel"), mapping)),
      kTolerance);
}

TEST_F(TableAgreementTest, EveryTableAgreesForATiltedNormal) {
  const Eigen::Vector3d normal = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const brdf::RusinkiewiczGrid grid;
  EXPECT_LT(Check("ggx_tilted", TableOf(AnalyticGgx(0.1), grid), normal), kTolerance);
  // The neural fit of steel is not isotropic near theta_h = 0: its input there still depends on
  // phi_d, and the table's theta_h = 0 row varies over phi_d by up to 0.13 in q, so f near
  // the mirror direction depends on the azimuth of h about n. With a tilted normal a float32 h
  // carries ~6e-8 of rounding across n, which is that azimuth when theta_h is below ~1e-4 rad:
  // the CPU (double) and the GPU (float) then see different phi_d. Measured: 0.16 at the
  // rotated mirror pairs (theta_h ~1e-8), 4.5e-4 from theta_h 1e-6, 2e-4 from 1e-5, 3.5e-5 from
  // 1e-4. So the tilted grid checks steel from theta_h = 1e-4 rad (0.006°); the +z grid, where
  // n × h is exact, checks every pair.
  EXPECT_LT(Check("steel_tilted_from_theta_h_1e-4", TableOf(brdf::ReadNbrdfMaterial("steel"), grid),
                  normal, 1e-4),
            kTolerance);
}

}  // namespace
}  // namespace brdfrig::render
