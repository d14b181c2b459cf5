#include "brdf/rusinkiewicz_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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

// The node measure integrates the cosine-weighted measure of direction pairs: a node whose
// neighbourhood lies below the horizon weighs nothing, and the measure's own moments come out
// of a weighted sum over nodes, E[cos θ] = ∫cos²θ dω / ∫cos θ dω = 2/3 for the light and the
// view alike and E[cos θi · cos θo] = (2/3)² (they are independent under this measure). The
// folded φd puts the light on the lower side at every node, so the sum takes both cosines.
TEST(RusinkiewiczTable, NodeMeasureIntegratesTheCosineWeightedMeasureOfDirectionPairs) {
  const RusinkiewiczGrid grid;
  const std::vector<double> w = NodeMeasure(grid);
  ASSERT_EQ(static_cast<int>(w.size()), grid.Cells());
  double total = 0, cos_in = 0, cos_both = 0;
  int below = 0;
  for (int ih = 0; ih < grid.theta_h; ++ih) {
    for (int id = 0; id < grid.theta_d; ++id) {
      for (int ip = 0; ip < grid.phi_d; ++ip) {
        const int node = grid.Index(ih, id, ip);
        ASSERT_GE(w[node], 0);
        Vec3 l, v;
        FromHalfDiffAngles(NodeAngles(grid, ih, id, ip), &l, &v);
        total += w[node];
        cos_in += w[node] * (std::max(l.z(), 0.0) + std::max(v.z(), 0.0)) / 2;
        cos_both += w[node] * std::max(l.z(), 0.0) * std::max(v.z(), 0.0);
        if (ih > 0 && id > 0 && ip > 0 && ih + 1 < grid.theta_h && id + 1 < grid.theta_d &&
            ip + 1 < grid.phi_d) {
          // Every cell around the node below the horizon: no pair of directions it stands for.
          bool all_below = true;
          for (int dh = -1; dh <= 1; ++dh)
            for (int dd = -1; dd <= 1; ++dd)
              for (int dp = -1; dp <= 1; ++dp) {
                Vec3 ln, vn;
                FromHalfDiffAngles(NodeAngles(grid, ih + dh, id + dd, ip + dp), &ln, &vn);
                all_below = all_below && ln.z() < 0;
              }
          if (all_below) {
            EXPECT_EQ(w[node], 0) << ih << " " << id << " " << ip;
            ++below;
          }
        }
      }
    }
  }
  EXPECT_GT(below, grid.Cells() / 10);
  EXPECT_NEAR(total / grid.Cells(), 1.0, 1e-12);
  EXPECT_NEAR(cos_in / total, 2.0 / 3.0, 0.01);
  EXPECT_NEAR(cos_both / total, 4.0 / 9.0, 0.01);
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
