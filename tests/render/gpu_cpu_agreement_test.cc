// The GLSL slice model against the CPU reference (brdf/slice_model.cc) on a dense grid of
// (theta_in, theta), grazing angles and extreme softness included. Runs on llvmpipe in CI.
#include <gtest/gtest.h>

#include <cmath>

#include "brdf/slice_model.h"
#include "render/gl_context.h"
#include "render/gpu_material.h"

namespace brdfrig::render {
namespace {

constexpr double kDeg = M_PI / 180;

brdf::Slice MakeSlice(double theta_in, double a1, double a2, double h, double x0) {
  brdf::Slice s;
  s.theta_in = theta_in;
  s.channel = {brdf::LobeParams{a1, a2, h, x0}, brdf::LobeParams{0.5 * a1 + a2, a2, 2 * h, x0},
               brdf::LobeParams{a1, 0.3 * a2, h, 1.5 * x0}};
  return s;
}

struct Agreement {
  double max_relative = 0;
  double theta_in_at = 0, theta_at = 0;
};

// Max over the grid of |gpu − cpu| / max(|cpu|, floor): relative where values are meaningful,
// absolute (scaled by the floor A2) on the lobe's flat tail.
Agreement Compare(const brdf::SliceModel& model, bool linear) {
  const int n_in = 256, n_theta = 256;
  cv::Mat angles(n_theta, n_in, CV_32FC2);
  for (int j = 0; j < n_theta; ++j) {
    for (int i = 0; i < n_in; ++i) {
      // theta_in from 0 to 89.9°, theta from 0 to 90°, denser near 0 where lobes are sharp.
      const double u = static_cast<double>(i) / (n_in - 1),
                   w = static_cast<double>(j) / (n_theta - 1);
      angles.at<cv::Vec2f>(j, i) = {static_cast<float>(u * 89.9 * kDeg),
                                    static_cast<float>(w * w * M_PI / 2)};
    }
  }
  const cv::Mat gpu = EvalSliceModelOnGpu(model, angles, linear);
  Agreement worst;
  const auto mode = linear ? brdf::Interpolation::kLinear : brdf::Interpolation::kSpline;
  for (int j = 0; j < n_theta; ++j) {
    for (int i = 0; i < n_in; ++i) {
      const cv::Vec2f a = angles.at<cv::Vec2f>(j, i);
      // The CPU evaluates at exactly the float angles the GPU saw.
      const brdf::Rgb cpu = model.EvalAngles(a[0], a[1], mode);
      const cv::Vec3f g = gpu.at<cv::Vec3f>(j, i);
      for (int c = 0; c < 3; ++c) {
        const double floor = std::max(1e-3, model.slices()[0].channel[c].a2);
        const double rel = std::abs(g[c] - cpu[c]) / std::max(std::abs(cpu[c]), floor);
        if (!(rel <= worst.max_relative)) worst = {rel, a[0], a[1]};
      }
    }
  }
  return worst;
}

class GpuCpuAgreementTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = CreateHeadlessContext().release(); }
  static void TearDownTestSuite() { delete context_; }
  static GlContext* context_;
};
GlContext* GpuCpuAgreementTest::context_ = nullptr;

TEST_F(GpuCpuAgreementTest, TypicalGlossyModelAgreesToFloatPrecision) {
  const brdf::SliceModel model(
      {MakeSlice(15 * kDeg, 20, 0.1, 0.02, 0.05), MakeSlice(25 * kDeg, 28, 0.1, 0.025, 0.06),
       MakeSlice(35 * kDeg, 40, 0.12, 0.03, 0.06), MakeSlice(50 * kDeg, 65, 0.15, 0.03, 0.07),
       MakeSlice(65 * kDeg, 120, 0.2, 0.04, 0.08), MakeSlice(80 * kDeg, 300, 0.3, 0.05, 0.1)});
  for (bool linear : {false, true}) {
    const Agreement a = Compare(model, linear);
    RecordProperty(linear ? "max_relative_linear" : "max_relative_spline",
                   std::to_string(a.max_relative));
    std::printf("%s: max relative error %.3g at theta_in %.2f°, theta %.3f°\n",
                linear ? "linear" : "spline", a.max_relative, a.theta_in_at / kDeg,
                a.theta_at / kDeg);
    EXPECT_LT(a.max_relative, 2e-5);
  }
}

TEST_F(GpuCpuAgreementTest, TinySoftnessStaysWithinFloatTolerance) {
  // h = 1e-4 rad: a near step. float32 angles carry ~6e-8 relative error, which moves
  // t = (theta − x0)/h by up to ~1e-4 — a relative change of ~1e-4 in the logistic.
  const brdf::SliceModel model({MakeSlice(20 * kDeg, 1e4, 0.05, 1e-4, 0.01),
                                MakeSlice(40 * kDeg, 2e4, 0.05, 1e-4, 0.012),
                                MakeSlice(60 * kDeg, 5e4, 0.05, 2e-4, 0.015)});
  const Agreement a = Compare(model, false);
  std::printf("tiny h: max relative error %.3g\n", a.max_relative);
  EXPECT_LT(a.max_relative, 1e-3);
}

TEST_F(GpuCpuAgreementTest, SingleSliceAndTwoSlicesAgree) {
  EXPECT_LT(
      Compare(brdf::SliceModel({MakeSlice(30 * kDeg, 5, 0.1, 0.05, 0.1)}), false).max_relative,
      2e-5);
  EXPECT_LT(Compare(brdf::SliceModel({MakeSlice(30 * kDeg, 5, 0.1, 0.05, 0.1),
                                      MakeSlice(60 * kDeg, 9, 0.2, 0.05, 0.1)}),
                    false)
                .max_relative,
            2e-5);
}

}  // namespace
}  // namespace brdfrig::render
