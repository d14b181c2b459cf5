// Captures built to break the reconstruction. Each checks that every number produced is finite,
// that the diagnostics say what the data cannot support, and accuracy where the data allow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/atomic_file.h"
#include "common/exr_io.h"
#include "reconstruct/measure_position.h"
#include "reconstruct/pipeline.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

using testing::SceneSpec;

// Edges averaged over 4×4 rays (exact to about 1/8 px, well inside what these cases ask of the
// pose), not the fixture's 16×16: thirteen captures, and the suite runs them instrumented too.
SceneSpec HardCase() {
  SceneSpec spec;
  spec.supersampling = 4;
  return spec;
}
using testing::SimulateCapture;

const char* kGgx = "{model: ggx, alpha: 0.1, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}";
const char* kRealistic =
    "[{type: shot_noise, full_well: 30000}, {type: read_noise, sigma: 0.0005}, "
    "{type: saturation, level: 1.0}, {type: quantization, bits: 14}]";

std::filesystem::path TempDir(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("brdfrig_hardcase_" + name);
}

void ExpectFinite(const brdf::Material& m) {
  ASSERT_FALSE(m.slices.empty());
  for (std::size_t i = 0; i < m.slices.size(); ++i) {
    EXPECT_TRUE(std::isfinite(m.slices[i].theta_in));
    for (const brdf::LobeParams& p : m.slices[i].channel) {
      EXPECT_TRUE(std::isfinite(p.a1) && std::isfinite(p.a2) && std::isfinite(p.h) &&
                  std::isfinite(p.x0))
          << "slice " << i;
      EXPECT_GE(p.a1, p.a2);
      EXPECT_GE(p.a2, 0);
      EXPECT_GT(p.h, 0);
    }
  }
  EXPECT_NO_THROW(m.Model());
}

bool AnyWarningContains(const ReconstructionResult& r, const std::string& text) {
  for (const auto& d : r.material.diagnostics) {
    for (const auto& w : d.warnings) {
      if (w.find(text) != std::string::npos) return true;
    }
  }
  for (const auto& w : r.warnings) {
    if (w.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(HardCases, HighlightSaturatedInEveryExposureIsFlagged) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.effects = kRealistic;
  spec.exposures = "[0.004, 0.008, 0.016]";  // the peak clips even in the shortest
  spec.positions = "[{camera_arm: 20, light_arm: -20}, {camera_arm: 40, light_arm: -40}]";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("saturated"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  EXPECT_TRUE(AnyWarningContains(r, "clipped in every exposure"));
  for (const auto& p : r.positions) EXPECT_GT(p.invalid_fraction, 0);
  // A bracket where the whole sample clips: the position is skipped with the reason.
  spec.exposures = "[0.03, 0.05, 0.0666667]";
  try {
    Reconstruct(SimulateCapture(TempDir("saturated_all"), spec), testing::SeedOnly());
    FAIL() << "an all-clipped capture was reconstructed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("add a shorter exposure"), std::string::npos) << e.what();
  }
}

TEST(HardCases, ASampleBelowTheNoiseFloorEverywhereIsAnErrorNamingTheFloorAndTheBracket) {
  SceneSpec spec = HardCase();
  spec.effects = kRealistic;
  // Four orders of magnitude darker than the paper: read noise even at 1/15 s.
  spec.brdf = "{model: lambert, albedo: [0.00005, 0.00005, 0.00005]}";
  spec.positions = "[{camera_arm: 20, light_arm: -20}, {camera_arm: 40, light_arm: -40}]";
  const CaptureSet capture = SimulateCapture(TempDir("below_floor"), spec);
  for (const ReconstructOptions& options : {testing::SeedOnly(), ReconstructOptions{}}) {
    try {
      const ReconstructionResult r = Reconstruct(capture, options);
      std::string report;
      for (const PositionReport& p : r.positions) {
        report += " p" + std::to_string(p.index) + ": " + std::to_string(p.direction_samples) +
                  " direction samples, " + std::to_string(p.below_noise_floor_fraction) +
                  " below the floor;";
      }
      FAIL() << "a capture that measured nothing was reconstructed (" << options.model
             << "):" << report;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("noise floor (0.10 % of full scale) at every position"),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("longest exposure (0.0667 s)"), std::string::npos) << what;
      EXPECT_NE(what.find("Lengthen the bracket"), std::string::npos) << what;
    }
  }
}

// What such a capture still says: the material is darker than the floor. Each block below it
// becomes an upper bound on the BRDF (the prior rung's), which must hold for the true one and
// account for every pixel it stands for.
TEST(HardCases, BlocksBelowTheNoiseFloorBecomeBoundsAboveTheTrueBrdf) {
  SceneSpec spec = HardCase();
  spec.effects = kRealistic;
  const double albedo = 0.00005;
  spec.brdf = "{model: lambert, albedo: [0.00005, 0.00005, 0.00005]}";
  spec.positions = "[{camera_arm: 20, light_arm: -20}]";
  const CaptureSet capture = SimulateCapture(TempDir("bounds"), spec);
  ASSERT_EQ(capture.positions.size(), 1u);
  MeasureState state;
  const MeasuredPosition m =
      MeasurePosition(capture.positions[0], capture.nominal, MeasureOptions{}, &state);
  EXPECT_TRUE(m.directions.samples.empty());
  ASSERT_FALSE(m.directions.bounds.empty());
  double pixels = 0, loosest = 0;
  for (const DirectionSample& b : m.directions.bounds) {
    pixels += b.weight;
    for (const double f : b.f) {
      EXPECT_GT(f, albedo / M_PI);
      loosest = std::max(loosest, f / (albedo / M_PI));
    }
  }
  EXPECT_EQ(pixels, m.directions.pixels_below_noise_floor);
  // The floor is a few read-noise sigmas, far above this material but not unboundedly: a bound
  // a million times the truth would be a units error, not a floor.
  EXPECT_LT(loosest, 1e4);
}

TEST(HardCases, APositionWhoseWholeSampleIsBelowTheNoiseFloorIsDegraded) {
  ReconstructionResult result;
  PositionReport dark;
  dark.index = 4;
  dark.used = true;
  dark.direction_samples = 0;
  dark.below_noise_floor_fraction = 1;
  PositionReport partly = dark;  // partly below the floor: measured where it is not
  partly.index = 5;
  partly.direction_samples = 30;
  partly.below_noise_floor_fraction = 0.7;
  result.positions = {dark, partly};
  ASSERT_EQ(result.Degraded().size(), 1u);
  EXPECT_EQ(result.Degraded()[0].rfind("p04: its whole sample is darker than the sensor's noise "
                                       "floor",
                                       0),
            0u)
      << result.Degraded()[0];
}

TEST(HardCases, HighlightOutsideTheCutoutFallsBackToTheNominalLight) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.positions = "[{camera_arm: 20, light_arm: -45}, {camera_arm: 30, light_arm: -30}]";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("outside"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  EXPECT_TRUE(AnyWarningContains(r, "nominal light used"));
}

TEST(HardCases, GrazingLightIsUsedOrSkippedWithAReasonNeverACrash) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.positions = "[{camera_arm: 30, light_arm: -30}, {camera_arm: 82, light_arm: -82}]";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("grazing"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  for (const auto& p : r.positions) {
    if (!p.used) {
      EXPECT_FALSE(p.skipped_reason.empty());
    }
  }
}

TEST(HardCases, NearlyLambertianSampleGivesFlatSlicesAtTheRightLevel) {
  SceneSpec spec = HardCase();
  spec.brdf = "{model: lambert, albedo: [0.4, 0.3, 0.2]}";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("lambert"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  EXPECT_TRUE(AnyWarningContains(r, "no highlight"));
  EXPECT_TRUE(AnyWarningContains(r, "no lobe"));
  for (const brdf::Slice& s : r.material.slices) {
    EXPECT_NEAR(s.channel[0].a2, 0.4 / M_PI, 0.01 * 0.4 / M_PI);  // radiometry to 1%
    EXPECT_NEAR(s.channel[2].a2, 0.2 / M_PI, 0.01 * 0.2 / M_PI);
  }
}

TEST(HardCases, NearMirrorSampleSaysTheLobeEdgeIsUnresolved) {
  SceneSpec spec = HardCase();
  spec.brdf = "{model: ggx, alpha: 0.004, f0: 0.9, diffuse: 0.05}";
  spec.exposures = "[0.00025, 0.008, 0.0666667]";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("mirror"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  EXPECT_TRUE(AnyWarningContains(r, "h unresolved") || AnyWarningContains(r, "clipped"));
}

TEST(HardCases, MissingAndCorruptPhotosSkipTheirPositionWithTheFileNamed) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  const auto dir = TempDir("missing");
  CaptureSet capture = SimulateCapture(dir, spec);
  std::filesystem::remove(capture.positions[0].frames[1].file);
  WriteFileAtomically(capture.positions[1].frames[0].file, "not a png");
  const ReconstructionResult r = Reconstruct(capture, testing::SeedOnly());
  ExpectFinite(r.material);
  EXPECT_EQ(r.material.slices.size(), 1u);
  std::string all;
  for (const std::string& w : r.warnings) all += w + "\n";
  ASSERT_EQ(r.warnings.size(), 2u) << all;
  EXPECT_NE(r.warnings[0].find(capture.positions[0].frames[1].file.filename().string()),
            std::string::npos)
      << r.warnings[0];
  // Nothing usable at all is an error that lists every reason.
  std::filesystem::remove(capture.positions[2].frames[0].file);
  EXPECT_THROW(Reconstruct(capture, testing::SeedOnly()), Error);
}

TEST(HardCases, NanAndInfInInputExrAreInvalidPixelsNotNumbers) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.positions = "[{camera_arm: 30, light_arm: -30}]";
  CaptureSet capture = SimulateCapture(TempDir("nan"), spec);
  for (BracketFrame& frame : capture.positions[0].frames) {
    cv::Mat photo = cv::imread(frame.file.string(), cv::IMREAD_UNCHANGED);
    cv::Mat linear;
    photo.convertTo(linear, CV_32FC3, 1.0 / 65535);
    for (int y = 200; y < 230; ++y) {
      for (int x = 300; x < 330; ++x) {
        linear.at<cv::Vec3f>(y, x) = cv::Vec3f(NAN, INFINITY, NAN);
      }
    }
    frame.file.replace_extension(".exr");
    WriteRadianceExr(frame.file, linear);
  }
  const ReconstructionResult r = Reconstruct(capture, testing::SeedOnly());
  ExpectFinite(r.material);
  ASSERT_TRUE(r.positions[0].used);
  EXPECT_EQ(r.positions[0].non_finite_pixels, 900);
  EXPECT_GT(r.positions[0].invalid_fraction, 0);
  // Masked, they no longer move the pose (issue 15: 6 mm before), and the result says it is
  // degraded rather than passing for clean.
  EXPECT_LT(r.positions[0].camera_disagreement_m, 2e-3);
  ASSERT_EQ(r.Degraded().size(), 1u);
  EXPECT_NE(r.Degraded()[0].find("p00: 900 NaN or infinite"), std::string::npos) << r.Degraded()[0];
}

TEST(HardCases, PartlyOccludedCornersStillGiveThePose) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.positions = "[{camera_arm: 30, light_arm: -30}]";
  CaptureSet capture = SimulateCapture(TempDir("occluded"), spec);
  // A dark object over one corner of the cut-out in every photo.
  Eigen::Vector2d corner;
  const geometry::CameraPose truth = capture.nominal.CameraAt(capture.positions[0].axis_readings);
  ASSERT_TRUE(
      geometry::ProjectToPixel(capture.nominal.intrinsics, truth, {0.05, 0.05, 0}, &corner));
  for (const BracketFrame& frame : capture.positions[0].frames) {
    cv::Mat photo = cv::imread(frame.file.string(), cv::IMREAD_UNCHANGED);
    cv::circle(photo, cv::Point(static_cast<int>(corner.x()), static_cast<int>(corner.y())), 8,
               cv::Scalar(500, 500, 500), cv::FILLED);
    cv::imwrite(frame.file.string(), photo);
  }
  const ReconstructionResult r = Reconstruct(capture, testing::SeedOnly());
  ExpectFinite(r.material);
  ASSERT_TRUE(r.positions[0].used);
  EXPECT_LT(r.positions[0].camera_disagreement_m, 2e-3);
}

TEST(HardCases, Noisy8BitCaptureRecoversTheResponseAndFitsFinite) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.sensor_format = "jpeg8";
  spec.effects =
      "[{type: shot_noise, full_well: 20000}, {type: read_noise, sigma: 0.001}, "
      "{type: saturation, level: 1.0}, {type: response_curve, curve: srgb}]";
  spec.exposures = "[0.001, 0.004, 0.016, 0.0666667]";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("jpeg"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  ASSERT_EQ(r.material.slices.size(), 3u);
  // The recovered response linearizes the photos: the slices agree with a linear 16-bit
  // capture of the same scene to 30% (measured: 26% at worst, the blue peak of the first
  // slice).
  spec.sensor_format = "png16";
  spec.effects =
      "[{type: shot_noise, full_well: 20000}, {type: read_noise, sigma: 0.001}, "
      "{type: saturation, level: 1.0}]";
  const ReconstructionResult linear =
      Reconstruct(SimulateCapture(TempDir("jpeg_ref"), spec), testing::SeedOnly());
  ASSERT_EQ(linear.material.slices.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    for (int c = 0; c < 3; ++c) {
      const brdf::LobeParams& got = r.material.slices[i].channel[c];
      const brdf::LobeParams& want = linear.material.slices[i].channel[c];
      EXPECT_NEAR(got.a1, want.a1, 0.3 * want.a1) << "slice " << i << " channel " << c;
      EXPECT_NEAR(got.a2, want.a2, 0.3 * want.a2) << "slice " << i << " channel " << c;
    }
  }
}

TEST(HardCases, VeryDarkSampleIsMeasuredAtItsLevel) {
  // Albedo 0.02: the sample sits near the bottom of every exposure, where read noise and
  // quantization dominate. The radiometry must still put it at albedo/pi.
  SceneSpec spec = HardCase();
  spec.brdf = "{model: lambert, albedo: [0.02, 0.015, 0.01]}";
  spec.effects = kRealistic;
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("dark"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  for (const brdf::Slice& s : r.material.slices) {
    EXPECT_NEAR(s.channel[0].a2, 0.02 / M_PI, 0.05 * 0.02 / M_PI);  // 5% at 1/50 of the paper
    EXPECT_NEAR(s.channel[2].a2, 0.01 / M_PI, 0.05 * 0.01 / M_PI);
  }
}

TEST(HardCases, HighlightAtTheEdgeOfTheCutoutIsMeasuredOrDeclared) {
  // camera 20°, light -29°: the mirror point lies about 3 mm inside a 100 mm cut-out's edge,
  // so part of the lobe is under the paper.
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.effects = kRealistic;
  spec.positions = "[{camera_arm: 20, light_arm: -29}, {camera_arm: 35, light_arm: -35}]";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("edge"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  ASSERT_TRUE(r.positions[0].used) << r.positions[0].skipped_reason;
  const LightEstimate& light = r.positions[0].light;
  if (light.from_highlight) {
    // Measured: then it must be right (the nominal light is the truth in this scene).
    EXPECT_LT(light.nominal_disagreement_rad, 1.0 * M_PI / 180);
  } else {
    EXPECT_TRUE(AnyWarningContains(r, "edge of the cut-out"));
  }
}

TEST(HardCases, ExtremeExposureRatioMergesToTheSameMaterial) {
  // 1 : 1000 between the shortest and longest exposure, only two of them: the merge has no
  // overlap where both are well exposed. The fit must agree with a well-bracketed capture.
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  spec.effects = kRealistic;
  spec.positions = "[{camera_arm: 30, light_arm: -30}]";
  const ReconstructionResult reference =
      Reconstruct(SimulateCapture(TempDir("ratio_ref"), spec), testing::SeedOnly());
  spec.exposures = "[0.0001, 0.1]";
  const ReconstructionResult r =
      Reconstruct(SimulateCapture(TempDir("ratio"), spec), testing::SeedOnly());
  ExpectFinite(r.material);
  ASSERT_EQ(r.material.slices.size(), 1u);
  for (int c = 0; c < 3; ++c) {
    const brdf::LobeParams& got = r.material.slices[0].channel[c];
    const brdf::LobeParams& want = reference.material.slices[0].channel[c];
    EXPECT_NEAR(got.a1, want.a1, 0.1 * want.a1) << "channel " << c;
    EXPECT_NEAR(got.h, want.h, 0.1 * want.h) << "channel " << c;
  }
  // 1 : 10000: the paper clips in the long exposure and is a few codes in the short one, so
  // its edges and its brightness are noise. The result is still finite, and the diagnostics
  // say the scale and the pose cannot be trusted.
  spec.exposures = "[0.00002, 0.2]";
  const ReconstructionResult bad =
      Reconstruct(SimulateCapture(TempDir("ratio_bad"), spec), testing::SeedOnly());
  ExpectFinite(bad.material);
  EXPECT_TRUE(AnyWarningContains(bad, "paper brightness spread"));
}

TEST(HardCases, OneWholePositionMissingIsSkippedAndTheRestFitted) {
  SceneSpec spec = HardCase();
  spec.brdf = kGgx;
  CaptureSet capture = SimulateCapture(TempDir("missing_position"), spec);
  for (const BracketFrame& frame : capture.positions[1].frames) {
    std::filesystem::remove(frame.file);
  }
  const ReconstructionResult r = Reconstruct(capture, testing::SeedOnly());
  ExpectFinite(r.material);
  EXPECT_EQ(r.material.slices.size(), 2u);
  EXPECT_FALSE(r.positions[1].used);
  EXPECT_TRUE(AnyWarningContains(r, capture.positions[1].frames[0].file.filename().string()));
}

}  // namespace
}  // namespace brdfrig::reconstruct
