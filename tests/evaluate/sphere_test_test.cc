#include "evaluate/sphere_test.h"

#include <gtest/gtest.h>

#include <cmath>

#include "brdf/analytic.h"
#include "common/error.h"

namespace brdfrig::evaluate {
namespace {

// The truth times a constant: the simplest wrong fit, with a known answer.
class Scaled : public brdf::Brdf {
 public:
  Scaled(const brdf::Brdf& base, double k) : base_(base), k_(k) {}
  brdf::Rgb Eval(const brdf::Vec3& l, const brdf::Vec3& v, const brdf::Vec3& n) const override {
    return k_ * base_.Eval(l, v, n);
  }
  std::string Name() const override { return "scaled"; }

 private:
  const brdf::Brdf& base_;
  double k_;
};

const brdf::Ggx kGgx({brdf::Rgb(0.3, 0.1, 0.05), brdf::Rgb(0.9, 0.6, 0.35), 0.2});

TEST(SphereTestTest, IdenticalMaterialsScoreInfinitePsnrAndZeroError) {
  const SphereTestResult r = SphereTest(kGgx, kGgx);
  ASSERT_EQ(r.lights.size(), 4u);
  for (const SphereLight& l : r.lights) {
    EXPECT_TRUE(std::isinf(l.psnr_db)) << r.Report();
    EXPECT_EQ(l.relative_rmse, 0);
    EXPECT_GT(l.scale, 0);
    // The sphere's inscribed disc: about pi/4 of the square.
    EXPECT_NEAR(static_cast<double>(l.pixels) / (128 * 128), M_PI / 4, 0.01);
  }
  EXPECT_NE(r.protocol.find("99th percentile"), std::string::npos);
  EXPECT_NE(r.Report().find("80°"), std::string::npos);
}

TEST(SphereTestTest, AKnownScaleErrorGivesThatRelativeRmse) {
  const Scaled brighter(kGgx, 1.1);
  const SphereTestResult r = SphereTest(kGgx, brighter);
  for (const SphereLight& l : r.lights) {
    EXPECT_NEAR(l.relative_rmse, 0.1, 1e-6) << l.light_angle_deg;
    // Finite and well below a perfect score, but a 10 % error is still a good fit.
    EXPECT_GT(l.psnr_db, 20);
    EXPECT_LT(l.psnr_db, 60);
  }
  EXPECT_NEAR(r.mean_relative_rmse, 0.1, 1e-6);
}

TEST(SphereTestTest, FiguresDoNotDependOnExposure) {
  const brdf::Ward wrong({brdf::Rgb(0.2, 0.2, 0.1), brdf::Rgb::Constant(0.1), 0.15});
  const SphereTestResult base = SphereTest(kGgx, wrong);
  const Scaled truth_k(kGgx, 7.5), wrong_k(wrong, 7.5);
  const SphereTestResult scaled = SphereTest(truth_k, wrong_k);
  for (std::size_t i = 0; i < base.lights.size(); ++i) {
    EXPECT_NEAR(base.lights[i].psnr_db, scaled.lights[i].psnr_db, 1e-3);
    EXPECT_NEAR(base.lights[i].relative_rmse, scaled.lights[i].relative_rmse, 1e-6);
    EXPECT_NEAR(scaled.lights[i].scale, 7.5 * base.lights[i].scale, 1e-4 * scaled.lights[i].scale);
  }
}

TEST(SphereTestTest, GrazingLightLightsLessOfTheSphere) {
  cv::Mat mask;
  const cv::Mat front = SphereRadiance(brdf::Lambert(brdf::Rgb::Constant(0.5)), 0, 64, &mask);
  const cv::Mat grazing =
      SphereRadiance(brdf::Lambert(brdf::Rgb::Constant(0.5)), 80 * M_PI / 180, 64);
  // The lit part of the visible disc: a half disc plus a half ellipse of minor axis cos 80°.
  EXPECT_NEAR(static_cast<double>(cv::countNonZero(grazing.reshape(1))) /
                  cv::countNonZero(front.reshape(1)),
              (1 + std::cos(80 * M_PI / 180)) / 2, 0.02);
  // The centre pixel of a Lambertian sphere lit from the camera: rho/pi · cos 0.
  EXPECT_NEAR(front.at<cv::Vec3f>(32, 32)[1], 0.5 / M_PI, 1e-3);
  EXPECT_EQ(mask.at<uchar>(0, 0), 0);
  EXPECT_EQ(mask.at<uchar>(32, 32), 255);
}

TEST(SphereTestTest, OptionsNameTheBadField) {
  SphereTestOptions options;
  options.light_angles_deg = {0, 95};
  try {
    options.Validate();
    FAIL();
  } catch (const OptionsError& e) {
    EXPECT_NE(std::string(e.what()).find("95"), std::string::npos) << e.what();
  }
  options = {};
  options.resolution = 2;
  EXPECT_THROW(options.Validate(), OptionsError);
}

TEST(SphereTestTest, SrgbEncodingMatchesTheStandard) {
  EXPECT_DOUBLE_EQ(SrgbEncode(0), 0);
  EXPECT_NEAR(SrgbEncode(1), 1, 1e-12);
  EXPECT_NEAR(SrgbEncode(0.18), 0.4613, 1e-3);
}

}  // namespace
}  // namespace brdfrig::evaluate
