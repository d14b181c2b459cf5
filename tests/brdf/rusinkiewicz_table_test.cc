#include "brdf/rusinkiewicz_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "brdf/analytic.h"
#include "brdf/material_file.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

Vec3 RandomDirection(std::mt19937& rng, double max_theta) {
  std::uniform_real_distribution<double> u(0, 1);
  const double t = max_theta * std::sqrt(u(rng)), p = 2 * M_PI * u(rng);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

TEST(RusinkiewiczTable, AnglesRoundTripThroughDirections) {
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 l = RandomDirection(rng, 1.5), v = RandomDirection(rng, 1.5);
    const HalfDiffAngles a = ToHalfDiffAngles(l, v);
    Vec3 l2, v2;
    FromHalfDiffAngles(a, &l2, &v2);
    // Same angles again (the pair is rotated about the normal and maybe mirrored).
    const HalfDiffAngles b = ToHalfDiffAngles(l2, v2);
    EXPECT_NEAR(a.theta_h, b.theta_h, 1e-9);
    EXPECT_NEAR(a.theta_d, b.theta_d, 1e-9);
    EXPECT_NEAR(a.phi_d, b.phi_d, 1e-7);
    // The pair is the same up to a rotation about the normal, a mirror and l <-> v.
    EXPECT_NEAR(std::min(l.z(), v.z()), std::min(l2.z(), v2.z()), 1e-9);
    EXPECT_NEAR(std::max(l.z(), v.z()), std::max(l2.z(), v2.z()), 1e-9);
    EXPECT_GE(a.phi_d, 0);
    EXPECT_LE(a.phi_d, M_PI / 2 + 1e-12);
  }
}

TEST(RusinkiewiczTable, TabulatedGgxMatchesTheModelAndIsReciprocal) {
  const Ggx ggx({Rgb(0.3, 0.2, 0.1), Rgb(0.9, 0.6, 0.3), 0.2});
  const RusinkiewiczGrid grid;
  const RusinkiewiczTable table(grid, TabulateBrdf(ggx, grid));
  std::mt19937 rng(5);
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 l = RandomDirection(rng, 1.3), v = RandomDirection(rng, 1.3);
    const Rgb truth = ggx.Eval(l, v, Vec3::UnitZ());
    const Rgb f = table.Eval(l, v, Vec3::UnitZ());
    ASSERT_TRUE(f.isFinite().all());
    EXPECT_NEAR(f[1], table.Eval(v, l, Vec3::UnitZ())[1], 1e-12 * f[1]);  // reciprocal
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(f[c] / truth[c] - 1));
  }
  // Trilinear interpolation of ln(f c + eps) on 64 x 32 x 8 nodes: a few per cent on a
  // roughness-0.2 lobe.
  EXPECT_LT(worst, 0.08);
  EXPECT_EQ(table.Eval(Vec3(0, 0.6, -0.8), Vec3::UnitZ(), Vec3::UnitZ())[0], 0);
  // A tilted normal: the same value in the rotated frame.
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.4, Vec3(1, 2, 0).normalized()).toRotationMatrix();
  const Vec3 l = Vec3(0.3, 0.1, 0.9).normalized(), v = Vec3(-0.2, -0.3, 0.8).normalized();
  EXPECT_NEAR(table.Eval(r * l, r * v, r * Vec3::UnitZ())[0], table.Eval(l, v, Vec3::UnitZ())[0],
              1e-9);
}

TEST(RusinkiewiczTable, MaterialFileRoundTripsWithinTheEncodingStep) {
  const Ggx ggx({Rgb(0.2, 0.3, 0.4), Rgb(0.5, 0.5, 0.5), 0.1});
  Material m;
  m.kind = ModelKind::kPrior;
  m.table = TabulateBrdf(ggx, m.table_grid);
  const std::string text = SerializeMaterial(m);
  EXPECT_LT(text.size(), 200000u);  // small enough to mail
  const Material back = ParseMaterial(text, "m.json");
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < m.table[c].size(); ++i) {
      worst = std::max(worst, std::abs(back.table[c][i] - m.table[c][i]));
    }
  }
  EXPECT_LT(worst, 2e-4);  // half a 16-bit step of q's range
  EXPECT_EQ(SerializeMaterial(back),
            SerializeMaterial(ParseMaterial(SerializeMaterial(back), "b")));

  std::string broken = text;
  broken.replace(broken.find("\"red\": \"") + 8, 4, "!!!!");
  try {
    ParseMaterial(broken, "m.json");
    ADD_FAILURE() << "bad base64 accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("table.red"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace brdfrig::brdf
