#include "brdf/slice_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/error.h"

namespace brdfrig::brdf {
namespace {

constexpr double kDeg = M_PI / 180;

Slice MakeSlice(double theta_in, double a1, double a2, double h, double x0) {
  Slice s;
  s.theta_in = theta_in;
  for (auto& c : s.channel) c = {a1, a2, h, x0};
  s.channel[1].a1 = a2 + 0.8 * (a1 - a2);  // make channels differ
  s.channel[2].a2 = a2 * 0.5;
  return s;
}

SliceModel FiveSlices() {
  return SliceModel(
      {MakeSlice(15 * kDeg, 20, 0.1, 0.02, 0.05), MakeSlice(25 * kDeg, 25, 0.1, 0.025, 0.06),
       MakeSlice(35 * kDeg, 40, 0.12, 0.03, 0.06), MakeSlice(50 * kDeg, 60, 0.15, 0.03, 0.07),
       MakeSlice(65 * kDeg, 120, 0.2, 0.04, 0.08)});
}

bool Finite(const Rgb& x) { return x.isFinite().all(); }

TEST(SliceAnglesTest, MirrorConfigurationGivesThetaZeroExactly) {
  const Vec3 n = Vec3::UnitZ();
  const Vec3 l = Vec3(std::sin(0.4), 0, std::cos(0.4));
  const Vec3 v = Vec3(-std::sin(0.4), 0, std::cos(0.4));
  const SliceAngles a = ComputeSliceAngles(l, v, n);
  EXPECT_NEAR(a.theta_in, 0.4, 1e-15);
  EXPECT_NEAR(a.theta, 0.0, 1e-15);
}

TEST(SliceAnglesTest, SmallAnglesAreAccurateWhereAcosIsNot) {
  const Vec3 n = Vec3::UnitZ();
  const double eps = 1e-9;
  const Vec3 l = Vec3(std::sin(eps), 0, std::cos(eps));
  EXPECT_NEAR(ComputeSliceAngles(l, n, n).theta_in, eps, 1e-18);
}

TEST(SliceModelTest, ThetaZeroIsFiniteAndNearPeak) {
  const SliceModel m = FiveSlices();
  const Rgb f = m.EvalAngles(35 * kDeg, 0.0);
  ASSERT_TRUE(Finite(f));
  // At theta = 0 the logistic is 1/(1+exp(-x0/h)) of the way from A2 to A1.
  const double expected = 0.12 + (40 - 0.12) / (1 + std::exp(-0.06 / 0.03));
  EXPECT_NEAR(f[0], expected, 1e-12 * expected);
}

TEST(SliceModelTest, ThetaInAtZeroUsesFirstSlice) {
  const SliceModel m = FiveSlices();
  const Rgb f = m.EvalAngles(0.0, 0.03);
  ASSERT_TRUE(Finite(f));
  EXPECT_NEAR(f[0], EvalLobe(m.slices()[0].channel[0], 0.03), 1e-14);
}

TEST(SliceModelTest, GrazingThetaInNearNinetyDegreesIsFinite) {
  const SliceModel m = FiveSlices();
  const Rgb f = m.EvalAngles(89.9 * kDeg, 0.1);
  ASSERT_TRUE(Finite(f));
  EXPECT_NEAR(f[0], EvalLobe(m.slices().back().channel[0], 0.1), 1e-14);
  // Through directions: light 89.9° from the normal, viewer at the mirror direction.
  const Vec3 n = Vec3::UnitZ();
  const double t = 89.9 * kDeg;
  const Rgb g = m.Eval({std::sin(t), 0, std::cos(t)}, {-std::sin(t), 0, std::cos(t)}, n);
  ASSERT_TRUE(Finite(g));
  EXPECT_GT(g[0], 0);
}

TEST(SliceModelTest, TinySoftnessIsAStepWithoutOverflow) {
  const SliceModel m({MakeSlice(30 * kDeg, 1000, 0.1, 1e-6, 0.05)});
  EXPECT_NEAR(m.EvalAngles(30 * kDeg, 0.05 - 1e-3)[0], 1000, 1e-9);
  EXPECT_NEAR(m.EvalAngles(30 * kDeg, 0.05 + 1e-3)[0], 0.1, 1e-9);
  EXPECT_NEAR(m.EvalAngles(30 * kDeg, 0.05)[0], 0.5 * (1000 + 0.1), 1e-9);
  EXPECT_TRUE(Finite(m.EvalAngles(30 * kDeg, M_PI)));
}

TEST(SliceModelTest, LargeSoftnessIsNearlyFlat) {
  const SliceModel m({MakeSlice(30 * kDeg, 2, 1, 10, 0.05)});
  const double f0 = m.EvalAngles(30 * kDeg, 0)[0], f1 = m.EvalAngles(30 * kDeg, M_PI / 2)[0];
  ASSERT_TRUE(std::isfinite(f0) && std::isfinite(f1));
  // The logistic slope is at most (A1-A2)/(4h): over pi/2 it changes by < 0.04.
  EXPECT_LT(std::abs(f0 - f1), (2 - 1) / (4 * 10.0) * M_PI / 2 + 1e-12);
}

TEST(SliceModelTest, EqualPeakAndFloorIsConstant) {
  const SliceModel m({MakeSlice(30 * kDeg, 0.3, 0.3, 0.02, 0.05)});
  for (double theta : {0.0, 0.05, 1.0, 3.0}) {
    EXPECT_NEAR(m.EvalAngles(30 * kDeg, theta)[0], 0.3, 1e-15);
  }
}

TEST(SliceModelTest, SingleSliceIsUsedAtEveryIncidence) {
  const SliceModel m({MakeSlice(40 * kDeg, 5, 0.1, 0.03, 0.06)});
  const Rgb a = m.EvalAngles(10 * kDeg, 0.04), b = m.EvalAngles(80 * kDeg, 0.04);
  ASSERT_TRUE(Finite(a));
  EXPECT_NEAR((a - b).abs().maxCoeff(), 0, 1e-15);
}

// Knots float cannot tell apart (the renderer's spline) are a clear error; the closest allowed
// stay finite and bounded.
TEST(SliceModelTest, NearlyEqualKnotsAreAnErrorAndTheClosestAllowedStayFiniteAndBounded) {
  EXPECT_THROW(SliceModel({MakeSlice(30 * kDeg, 5, 0.1, 0.03, 0.06),
                           MakeSlice(30 * kDeg + 1e-12, 50, 0.1, 0.03, 0.06)}),
               Error);
  const SliceModel m({MakeSlice(30 * kDeg, 5, 0.1, 0.03, 0.06),
                      MakeSlice(30 * kDeg + kMinKnotSpacing, 50, 0.1, 0.03, 0.06),
                      MakeSlice(50 * kDeg, 10, 0.1, 0.03, 0.06)});
  for (double t = 25 * kDeg; t < 55 * kDeg; t += 0.1 * kDeg) {
    const Rgb f = m.EvalAngles(t, 0.02);
    ASSERT_TRUE(Finite(f)) << t;
    EXPECT_LE(f[0], EvalLobe({50, 0.1, 0.03, 0.06}, 0.02) * (1 + 1e-12));
    EXPECT_GE(f[0], 0);
  }
}

TEST(SliceModelTest, ExtrapolationBeyondEndKnotsIsConstant) {
  const SliceModel m = FiveSlices();
  for (double theta : {0.0, 0.05, 0.3}) {
    EXPECT_NEAR((m.EvalAngles(1 * kDeg, theta) - m.EvalAngles(15 * kDeg, theta)).abs().maxCoeff(),
                0, 1e-14);
    EXPECT_NEAR((m.EvalAngles(85 * kDeg, theta) - m.EvalAngles(65 * kDeg, theta)).abs().maxCoeff(),
                0, 1e-14);
  }
}

TEST(SliceModelTest, InterpolatesExactlyAtKnots) {
  const SliceModel m = FiveSlices();
  for (const Slice& s : m.slices()) {
    for (auto mode : {Interpolation::kSpline, Interpolation::kLinear}) {
      const Rgb f = m.EvalAngles(s.theta_in, 0.04, mode);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], EvalLobe(s.channel[c], 0.04), 1e-12);
    }
  }
}

TEST(SliceModelTest, SplineIsC1AtKnotsWhereLinearIsNot) {
  const SliceModel m = FiveSlices();
  const double e = 1e-6;
  for (std::size_t k = 1; k + 1 < m.slices().size(); ++k) {
    const double t = m.slices()[k].theta_in;
    auto slope = [&](double a, double b, Interpolation mode) {
      return (m.EvalAngles(b, 0.04, mode)[0] - m.EvalAngles(a, 0.04, mode)[0]) / (b - a);
    };
    const double left = slope(t - 2 * e, t - e, Interpolation::kSpline);
    const double right = slope(t + e, t + 2 * e, Interpolation::kSpline);
    EXPECT_NEAR(left, right, 1e-3 * std::max(1.0, std::abs(left))) << "knot " << k;
    const double lin_left = slope(t - 2 * e, t - e, Interpolation::kLinear);
    const double lin_right = slope(t + e, t + 2 * e, Interpolation::kLinear);
    EXPECT_GT(std::abs(lin_left - lin_right), 1.0) << "linear should have a kink at knot " << k;
  }
}

TEST(SliceModelTest, SplineNeverOvershootsNeighbouringKnotValues) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Slice> slices;
    double t = 5 * kDeg;
    for (int k = 0; k < 6; ++k) {
      t += (2 + 15 * u(rng)) * kDeg;
      const double a2 = 0.5 * u(rng) * u(rng);
      slices.push_back(
          MakeSlice(t, a2 + 100 * u(rng) * u(rng), a2, 0.005 + 0.1 * u(rng), 0.2 * u(rng)));
    }
    const SliceModel m(slices);
    for (int s = 0; s < 400; ++s) {
      const double theta_in =
          slices.front().theta_in + u(rng) * (slices.back().theta_in - slices.front().theta_in);
      const double theta = 0.5 * u(rng);
      const Rgb f = m.EvalAngles(theta_in, theta);
      const auto hi = std::upper_bound(slices.begin(), slices.end(), theta_in,
                                       [](double x, const Slice& q) { return x < q.theta_in; });
      const Slice& b = *hi;
      const Slice& a = *(hi - 1);
      for (int c = 0; c < 3; ++c) {
        const double ya = EvalLobe(a.channel[c], theta), yb = EvalLobe(b.channel[c], theta);
        ASSERT_GE(f[c], 0);
        ASSERT_LE(f[c], std::max(ya, yb) * (1 + 1e-12) + 1e-15);
        ASSERT_GE(f[c], std::min(ya, yb) * (1 - 1e-12) - 1e-15);
      }
    }
  }
}

TEST(SliceModelTest, BelowHorizonIsZero) {
  const SliceModel m = FiveSlices();
  const Vec3 n = Vec3::UnitZ();
  EXPECT_EQ(m.Eval({0, 0, -1}, {0, 0, 1}, n).maxCoeff(), 0);
  EXPECT_EQ(m.Eval({0, 0, 1}, {1, 0, -0.1}, n).maxCoeff(), 0);
}

TEST(SliceModelTest, HugeParametersDoNotOverflow) {
  const SliceModel m({MakeSlice(30 * kDeg, 1e300, 0, 1e-300, 1e-3)});
  const Rgb f = m.EvalAngles(30 * kDeg, 1.0);
  EXPECT_TRUE(Finite(f));
  EXPECT_EQ(f[0], 0);
}

TEST(SliceModelValidationTest, RejectsBadParametersNamingTheField) {
  auto message = [](std::vector<Slice> slices) {
    try {
      SliceModel m(std::move(slices));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Slice ok = MakeSlice(0.3, 5, 0.1, 0.02, 0.05);
  Slice bad_h = ok;
  bad_h.channel[1].h = -0.01;
  EXPECT_EQ(message({ok, MakeSlice(0.5, 5, 0.1, 0.02, 0.05), bad_h}).substr(0, 40),
            "slices[2].theta_in: must be greater than");
  bad_h.theta_in = 0.9;
  EXPECT_EQ(message({ok, MakeSlice(0.5, 5, 0.1, 0.02, 0.05), bad_h}),
            "slices[2].green.h: must be > 0, got -0.01");
  Slice inverted = ok;
  inverted.channel[0].a1 = 0.01;
  EXPECT_NE(message({inverted}).find("slices[0].red.A1: must be >= A2"), std::string::npos);
  Slice nan = ok;
  nan.channel[2].x0 = NAN;
  EXPECT_NE(message({nan}).find("slices[0].blue.x0: must be finite"), std::string::npos);
  EXPECT_NE(message({ok, ok}).find("slices[1].theta_in"), std::string::npos);
  EXPECT_NE(message({}).find("at least one slice"), std::string::npos);
}

}  // namespace
}  // namespace brdfrig::brdf
