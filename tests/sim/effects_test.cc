// Each effect changes the image exactly as specified, and listing it with `enabled: false`
// (or not listing it) gives the ideal image bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "brdf/analytic.h"
#include "brdf/metrics.h"
#include "sim/simulator.h"
#include "sim/world.h"
#include "test_scene.h"

namespace brdfrig::sim {
namespace {

using testing::TestScene;

constexpr double kDegree = M_PI / 180.0;
constexpr double kExposure = 0.01;
constexpr std::uint64_t kFrame = 3;
const geometry::AxisPositions kPositions = {{"camera_arm", 10 * kDegree},
                                            {"light_arm", -5 * kDegree}};

cv::Mat Photo(const Scene& scene, double exposure = kExposure) {
  return Simulator(scene).RenderCameraImage(kPositions, exposure, kFrame);
}

cv::Mat Ideal(double exposure = kExposure) { return Photo(TestScene(), exposure); }

bool BitIdentical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && a.isContinuous() && b.isContinuous() &&
         std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;
}

Scene WithEffect(const std::string& effect, bool enabled = true) {
  return TestScene("effects:\n  - {" + effect + (enabled ? "" : ", enabled: false") + "}\n");
}

// Every effect, listed but disabled, is the ideal camera bit for bit (and so are its photos).
TEST(EffectsTest, EveryEffectListedButDisabledIsTheIdealImageBitForBit) {
  const std::vector<std::string> effects = {
      "type: area_light, radius: 0.02, samples: 8",
      "type: ambient, radiance: 0.1",
      "type: radial_distortion, k1: -0.2",
      "type: vignetting, falloff: cos4",
      "type: shot_noise, full_well: 1000",
      "type: read_noise, sigma: 0.01",
      "type: saturation, level: 0.5",
      "type: quantization, bits: 8",
      "type: response_curve, curve: srgb",
      "type: mechanical_error, backlash_deg: 1, jitter_deg: 0.1"};
  const cv::Mat ideal = Ideal();
  std::string all = "effects:\n";
  for (const std::string& e : effects) {
    const Scene enabled = WithEffect(e);
    const Scene disabled = WithEffect(e, false);
    EXPECT_TRUE(BitIdentical(Photo(disabled), ideal)) << e;
    if (e.find("mechanical_error") == std::string::npos) {
      EXPECT_FALSE(BitIdentical(Photo(enabled), ideal)) << e;
    }
    all += "  - {" + e + ", enabled: false}\n";
  }
  const Scene all_disabled = TestScene(all);
  const Simulator simulator(all_disabled);
  EXPECT_TRUE(BitIdentical(Photo(all_disabled), ideal));
  EXPECT_EQ(simulator.EncodePhoto(Photo(all_disabled)), simulator.EncodePhoto(ideal));
}

TEST(EffectsTest, Cos4VignettingScalesEachPixelByCosineToTheFourth) {
  const cv::Mat ideal = Ideal();
  const cv::Mat vignetted = Photo(WithEffect("type: vignetting, falloff: cos4"));
  for (int v = 0; v < ideal.rows; v += 3) {
    for (int u = 0; u < ideal.cols; u += 3) {
      const double tan2 = std::pow((u - 160.0) / 400, 2) + std::pow((v - 120.0) / 400, 2);
      const double factor = 1 / ((1 + tan2) * (1 + tan2));
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(vignetted.at<cv::Vec3f>(v, u)[c], ideal.at<cv::Vec3f>(v, u)[c] * factor,
                    1e-6 * ideal.at<cv::Vec3f>(v, u)[c] + 1e-12);
      }
    }
  }
}

TEST(EffectsTest, PolynomialVignettingReachesOnePlusA1PlusA2AtTheCorner) {
  const cv::Mat ideal = Ideal();
  const cv::Mat vignetted =
      Photo(WithEffect("type: vignetting, falloff: polynomial, a1: -0.3, a2: -0.1"));
  // Pixel (0, 0) is exactly one half-diagonal from the principal point (160, 120).
  EXPECT_NEAR(vignetted.at<cv::Vec3f>(0, 0)[1], 0.6 * ideal.at<cv::Vec3f>(0, 0)[1],
              1e-6 * ideal.at<cv::Vec3f>(0, 0)[1]);
  EXPECT_EQ(vignetted.at<cv::Vec3f>(120, 160), ideal.at<cv::Vec3f>(120, 160));
}

TEST(EffectsTest, ShotNoiseIsPoissonWithTheFullWellScale) {
  const double full_well = 1000;
  const cv::Mat ideal = Ideal();
  const cv::Mat noisy = Photo(WithEffect("type: shot_noise, full_well: 1000"));
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int i = 0; i < static_cast<int>(ideal.total() * 3); ++i) {
    const double mean = ideal.ptr<float>()[i];
    if (mean < 0.01) continue;
    const double z = (noisy.ptr<float>()[i] - mean) / std::sqrt(mean / full_well);
    sum += z;
    sum2 += z * z;
    ++n;
  }
  ASSERT_GT(n, 100000);
  const double mean_z = sum / n;
  EXPECT_NEAR(mean_z, 0, 0.02);
  EXPECT_NEAR(std::sqrt(sum2 / n - mean_z * mean_z), 1.0, 0.02);
  // Counts are whole electrons.
  const double electrons = noisy.ptr<float>()[1000] * full_well;
  EXPECT_NEAR(electrons, std::round(electrons), 1e-3);
}

TEST(EffectsTest, ReadNoiseIsAdditiveGaussianWithTheGivenSigma) {
  const cv::Mat ideal = Ideal();
  const cv::Mat noisy = Photo(WithEffect("type: read_noise, sigma: 0.01"));
  cv::Mat diff;
  cv::subtract(noisy, ideal, diff, cv::noArray(), CV_64FC3);
  cv::Scalar mean, stddev;
  cv::meanStdDev(diff.reshape(1), mean, stddev);
  EXPECT_NEAR(mean[0], 0, 1e-4);
  EXPECT_NEAR(stddev[0], 0.01, 0.0002);
}

TEST(EffectsTest, SaturationClipsAtTheLevelAndNowhereElse) {
  const double exposure = 0.2;  // bright enough that the paper exceeds 0.5
  const cv::Mat ideal = Ideal(exposure);
  const cv::Mat clipped = Photo(WithEffect("type: saturation, level: 0.5"), exposure);
  int saturated = 0;
  for (int i = 0; i < static_cast<int>(ideal.total() * 3); ++i) {
    const float a = ideal.ptr<float>()[i], b = clipped.ptr<float>()[i];
    ASSERT_EQ(b, std::min(a, 0.5f));
    saturated += a > 0.5f;
  }
  EXPECT_GT(saturated, 1000);
}

TEST(EffectsTest, QuantizationRoundsToTheAdcLevels) {
  const cv::Mat ideal = Ideal();
  const cv::Mat q = Photo(WithEffect("type: quantization, bits: 8"));
  for (int i = 0; i < static_cast<int>(ideal.total() * 3); ++i) {
    const double value = q.ptr<float>()[i];
    const double code = value * 255;
    ASSERT_NEAR(code, std::round(code), 1e-4);
    ASSERT_LE(std::abs(value - std::clamp<double>(ideal.ptr<float>()[i], 0, 1)), 0.5 / 255 + 1e-6);
  }
}

TEST(EffectsTest, ResponseCurvesApplyTheirFormulaToClampedSignal) {
  const cv::Mat ideal = Ideal(0.05);
  const cv::Mat srgb = Photo(WithEffect("type: response_curve, curve: srgb"), 0.05);
  const cv::Mat gamma = Photo(WithEffect("type: response_curve, curve: gamma, gamma: 2.2"), 0.05);
  const cv::Mat table =
      Photo(WithEffect("type: response_curve, curve: table, values: [0, 0.8, 1]"), 0.05);
  for (int i = 0; i < static_cast<int>(ideal.total() * 3); i += 11) {
    const double x = std::clamp<double>(ideal.ptr<float>()[i], 0, 1);
    const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
    ASSERT_NEAR(srgb.ptr<float>()[i], s, 1e-6);
    ASSERT_NEAR(gamma.ptr<float>()[i], std::pow(x, 1 / 2.2), 1e-6);
    const double t = x < 0.5 ? 1.6 * x : 0.8 + 0.4 * (x - 0.5);
    ASSERT_NEAR(table.ptr<float>()[i], t, 1e-6);
  }
}

TEST(EffectsTest, RadialDistortionTracesRaysThroughTheDistortedLens) {
  const Scene scene = WithEffect("type: radial_distortion, k1: -0.2, k2: 0.05");
  const Simulator simulator(scene);
  const TrueGeometry g = simulator.GeometryAt({});
  EXPECT_DOUBLE_EQ(g.intrinsics.k1, -0.2);
  const cv::Mat distorted = simulator.RenderRadiance({});
  const cv::Mat ideal = Simulator(TestScene()).RenderRadiance({});
  int checked = 0;
  for (int v = 0; v < 240; v += 4) {
    for (int u = 0; u < 320; u += 4) {
      const geometry::Vec3 ray = geometry::PixelRayInWorld(g.intrinsics, g.camera, {u, v});
      const geometry::Vec3 c = g.camera.CenterInWorld();
      const geometry::Vec3 p = c - c.z() / ray.z() * ray;
      const double ax = std::abs(p.x()), ay = std::abs(p.y());
      if (!(ax > 0.052 || ay > 0.042) || ax > 0.148 || ay > 0.148) continue;  // paper only
      const geometry::Vec3 l = geometry::Vec3(0.05, 0.1, 0.6) - p;
      const double expected = 0.7 / M_PI * 2.0 * (l.z() / l.norm()) / l.squaredNorm();
      ASSERT_NEAR(distorted.at<cv::Vec3f>(v, u)[0], expected, 1e-5 * expected);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1500);
  // Barrel distortion pulls the corners in: the corner pixel sees a point further out.
  EXPECT_NE(distorted.at<cv::Vec3f>(0, 0), ideal.at<cv::Vec3f>(0, 0));
  EXPECT_EQ(distorted.at<cv::Vec3f>(120, 160), ideal.at<cv::Vec3f>(120, 160));
}

TEST(EffectsTest, AreaLightSoftensHighlightsAndBarelyChangesDiffusePaper) {
  const std::string mirror = "{model: ggx, alpha: 0.02, f0: 1.0}";
  const Scene point = TestScene("", mirror);
  const Scene area =
      TestScene("effects:\n  - {type: area_light, radius: 0.02, samples: 64}\n", mirror);
  const geometry::AxisPositions positions = {{"camera_arm", 30 * kDegree},
                                             {"light_arm", -20 * kDegree}};
  const cv::Mat a = Simulator(point).RenderRadiance(positions);
  const cv::Mat b = Simulator(area).RenderRadiance(positions);
  cv::Mat ga, gb;
  cv::extractChannel(a, ga, 1);
  cv::extractChannel(b, gb, 1);
  double peak_a = 0, peak_b = 0;
  cv::minMaxLoc(ga, nullptr, &peak_a);
  cv::minMaxLoc(gb, nullptr, &peak_b);
  EXPECT_LT(peak_b, 0.8 * peak_a);
  EXPECT_GT(cv::countNonZero(gb > 0.5 * peak_b), cv::countNonZero(ga > 0.5 * peak_a));
  // The highlight's total power is about the same: the light's intensity is only spread out.
  const cv::Rect sample_region(100, 60, 120, 120);
  EXPECT_NEAR(cv::sum(gb(sample_region))[0], cv::sum(ga(sample_region))[0],
              0.05 * cv::sum(ga(sample_region))[0]);
  // Diffuse paper far from the light sees almost a point: (r/d)² ≈ 1e-3.
  EXPECT_NEAR(gb.at<float>(10, 160), ga.at<float>(10, 160), 2e-3 * ga.at<float>(10, 160));
}

TEST(EffectsTest, AmbientAddsSkyRadianceTimesDirectionalAlbedo) {
  const Scene scene = WithEffect("type: ambient, radiance: [0.1, 0.2, 0.3]");
  const Simulator simulator(scene);
  RenderOptions dark;
  dark.light_on = false;
  const cv::Mat ambient_only = simulator.RenderRadiance({}, dark);
  // Paper (albedo 0.7) and table (0.05) reflect exactly albedo × sky radiance.
  const cv::Vec3f paper = ambient_only.at<cv::Vec3f>(10, 160);
  EXPECT_NEAR(paper[2], 0.07, 1e-7);
  EXPECT_NEAR(paper[1], 0.14, 1e-7);
  EXPECT_NEAR(paper[0], 0.21, 1e-7);
  EXPECT_NEAR(ambient_only.at<cv::Vec3f>(120, 2)[1], 0.01, 1e-8);
  // The sample (seen straight on at the centre) reflects its directional albedo.
  const brdf::Ggx ggx({brdf::Rgb::Constant(0.1), brdf::Rgb::Constant(0.5), 0.1});
  const double albedo = brdf::DirectionalAlbedo(ggx, 0.0)[1];
  EXPECT_NEAR(ambient_only.at<cv::Vec3f>(120, 160)[1], 0.2 * albedo, 0.01 * 0.2 * albedo);
  // With the light on, ambient adds on top of the direct light.
  const cv::Mat lit = simulator.RenderRadiance({});
  const cv::Mat ideal = Simulator(TestScene()).RenderRadiance({});
  EXPECT_NEAR(lit.at<cv::Vec3f>(10, 160)[1] - ideal.at<cv::Vec3f>(10, 160)[1], 0.14, 1e-6);
}

TEST(EffectsTest, MechanicalBacklashShiftsTheArmAgainstTheDirectionOfApproach) {
  SimWorld ideal(TestScene());
  SimWorld worn(WithEffect("type: mechanical_error, backlash_deg: 1.0"));
  // Approach 20° from below: the arm lags half the backlash behind.
  EXPECT_DOUBLE_EQ(worn.MoveAxis("camera_arm", 20 * kDegree).position, 20 * kDegree);
  EXPECT_NEAR(worn.TruePositions()["camera_arm"], 19.5 * kDegree, 1e-12);
  worn.MoveAxis("camera_arm", 30 * kDegree);
  worn.MoveAxis("camera_arm", 20 * kDegree);  // from above now
  EXPECT_NEAR(worn.TruePositions()["camera_arm"], 20.5 * kDegree, 1e-12);
  ideal.MoveAxis("camera_arm", 20 * kDegree);
  EXPECT_DOUBLE_EQ(ideal.TruePositions()["camera_arm"], 20 * kDegree);
  // The reported reading is the same; what the camera sees is not.
  EXPECT_DOUBLE_EQ(worn.AxisStatus("camera_arm").position, 20 * kDegree);
  const cv::Mat a = ideal.simulator().RenderRadiance(ideal.TruePositions());
  const cv::Mat b = worn.simulator().RenderRadiance(worn.TruePositions());
  EXPECT_GT(cv::norm(a, b, cv::NORM_INF), 0.0);
  SimWorld disabled(WithEffect("type: mechanical_error, backlash_deg: 1.0", false));
  disabled.MoveAxis("camera_arm", 20 * kDegree);
  EXPECT_TRUE(BitIdentical(disabled.simulator().RenderRadiance(disabled.TruePositions()), a));
}

TEST(EffectsTest, MechanicalJitterIsSeededAndHasTheGivenSpread) {
  auto run = [](const std::string& extra) {
    SimWorld world(TestScene(extra + "effects:\n  - {type: mechanical_error, jitter_deg: 0.1}\n"));
    std::vector<double> errors;
    for (int i = 0; i < 2000; ++i) {
      const double target = (i % 2 ? 10 : 20) * kDegree;
      world.MoveAxis("light_arm", target);
      errors.push_back((world.TruePositions()["light_arm"] - target) / kDegree);
    }
    return errors;
  };
  const std::vector<double> a = run(""), b = run("");
  EXPECT_EQ(a, b);
  double sum2 = 0;
  for (double e : a) sum2 += e * e;
  EXPECT_NEAR(std::sqrt(sum2 / a.size()), 0.1, 0.006);
}

}  // namespace
}  // namespace brdfrig::sim
