// Scene files: the shipped default scene loads, and every mistake is a FileError that names
// file:line:column and says what was expected.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "brdf/material_file.h"
#include "coverage/designer.h"

#include "sim/scene.h"
#include "test_scene.h"

namespace brdfrig::sim {
namespace {

using testing::BaseSceneYaml;
using ::testing::HasSubstr;

constexpr double kDegree = M_PI / 180.0;

// Line (1-based) on which the base scene ends; extra text starts on the next line.
int BaseLines() {
  const std::string base = BaseSceneYaml();
  return static_cast<int>(std::count(base.begin(), base.end(), '\n'));
}

std::string ErrorOf(const std::string& extra) {
  try {
    LoadSceneString(BaseSceneYaml() + extra, "scene.yaml");
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

std::string At(int extra_line) { return "scene.yaml:" + std::to_string(BaseLines() + extra_line); }

TEST(SceneTest, DefaultSceneLoadsWithSixDesignedPositions) {
  const Scene scene = LoadScene(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/ggx.yaml");
  EXPECT_EQ(scene.rig.intrinsics.width, 1600);
  EXPECT_EQ(scene.rig.intrinsics.height, 1200);
  ASSERT_EQ(scene.capture.positions.size(), 6u);
  EXPECT_EQ(scene.capture.validation, std::vector<bool>(6, false));
  EXPECT_EQ(scene.capture.exposures.size(), 3u);
  EXPECT_EQ(scene.sample.brdf->Name().substr(0, 3), "ggx");
  EXPECT_TRUE(scene.effects.shot_noise.has_value());
  EXPECT_FALSE(scene.effects.vignetting.has_value());
  EXPECT_NE(scene.capture.design.find("designed plan"), std::string::npos);
  // The designed plan (docs/coverage.md): every position within the design's constraints, one
  // near retro-reflection, one with grazing light, and some off the specular direction.
  const coverage::DesignOptions options;
  const coverage::CoverageMap map =
      coverage::ComputeCoverage(scene.rig, scene.capture.positions, scene.capture.validation);
  bool retro = false, grazing = false;
  int off_specular = 0;
  for (const coverage::PositionCoverage& c : map.positions) {
    EXPECT_EQ(coverage::CheckDesignConstraints(scene.rig, c.axes, options), "");
    retro |= c.theta_d_min < 15 * kDegree;
    grazing |= c.theta_in >= 70 * kDegree;
    off_specular += c.theta_h_min > 2 * kDegree;
  }
  EXPECT_TRUE(retro);
  EXPECT_TRUE(grazing);
  EXPECT_GE(off_specular, 2);
}

TEST(SceneTest, EffectsAreParsedWithTheirValues) {
  const Scene scene = LoadSceneString(BaseSceneYaml() + R"(effects:
  - {type: response_curve, curve: gamma, gamma: 2.0}
  - {type: vignetting, falloff: polynomial, a1: -0.2}
  - {type: quantization, bits: 12}
  - {type: mechanical_error, backlash_deg: 0.5}
  - {type: read_noise, sigma: 0.01, enabled: false}
)",
                                      "scene.yaml");
  ASSERT_TRUE(scene.effects.response_curve);
  EXPECT_DOUBLE_EQ(scene.effects.response_curve->gamma, 2.0);
  EXPECT_DOUBLE_EQ(scene.effects.vignetting->a1, -0.2);
  EXPECT_EQ(scene.effects.quantization->bits, 12);
  EXPECT_NEAR(scene.effects.mechanical_error->backlash, 0.5 * kDegree, 1e-15);
  EXPECT_FALSE(scene.effects.read_noise.has_value());
  EXPECT_EQ(scene.effects.Describe(), "vignetting, quantization, response_curve, mechanical_error");
  EXPECT_EQ(scene.Ideal().effects.Describe(), "none (ideal camera)");
}

TEST(SceneTest, UnknownEffectNameIsAnErrorAtItsLine) {
  const std::string error = ErrorOf("effects:\n  - {type: vignetting}\n  - {type: blur, px: 2}\n");
  EXPECT_THAT(error, HasSubstr(At(3) + ":"));
  EXPECT_THAT(error, HasSubstr("unknown effect 'blur' (known: area_light"));
}

TEST(SceneTest, BadEffectValueIsAnErrorAtItsLine) {
  EXPECT_THAT(ErrorOf("effects:\n  - type: read_noise\n    sigma: -0.1\n"),
              HasSubstr(At(3) + ":12: effects[0].sigma: must be in [0, 1], got -0.1"));
  EXPECT_THAT(ErrorOf("effects:\n  - {type: quantization, bits: 40}\n"), HasSubstr(At(2) + ":"));
  EXPECT_THAT(
      ErrorOf("effects:\n  - {type: response_curve, curve: table, values: [0, 0.6, 0.5]}\n"),
      HasSubstr("values must be non-decreasing"));
}

TEST(SceneTest, UnknownKeyInsideAnEffectIsAnError) {
  EXPECT_THAT(ErrorOf("effects:\n  - type: shot_noise\n    fullwell: 100\n"),
              HasSubstr(At(3) + ":5: unknown key 'effects[0].fullwell'"));
}

TEST(SceneTest, DuplicateEffectIsAnError) {
  EXPECT_THAT(
      ErrorOf("effects:\n  - {type: ambient, radiance: 1}\n  - {type: ambient, radiance: 2}\n"),
      HasSubstr("effect 'ambient' is listed twice"));
}

TEST(SceneTest, UnknownTopLevelKeyIsAnError) {
  EXPECT_THAT(ErrorOf("lighting: {}\n"), HasSubstr(At(1) + ":1: unknown key 'lighting'"));
}

TEST(SceneTest, UnknownBrdfModelIsAnError) {
  try {
    LoadSceneString(BaseSceneYaml("{model: phong, exponent: 3}"), "scene.yaml");
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scene.yaml:10:"));
    EXPECT_THAT(e.what(), HasSubstr("unknown model 'phong'"));
  }
}

TEST(SceneTest, MissingModelFileIsReportedAtTheSceneLine) {
  try {
    LoadSceneString(BaseSceneYaml("{model: slices, file: nowhere/material.json}"), "scene.yaml");
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scene.yaml:10:"));
    EXPECT_THAT(e.what(), HasSubstr("material.json"));
  }
}

TEST(SceneTest, CameraDistortionMustBeAnEffect) {
  std::string yaml = BaseSceneYaml();
  yaml.replace(yaml.find("focal_px"), 0, "distortion: [-0.1, 0], ");
  try {
    LoadSceneString(yaml, "scene.yaml");
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("scene.yaml:2:"));
    EXPECT_THAT(e.what(), HasSubstr("radial_distortion effect"));
  }
}

TEST(SceneTest, CapturePositionsNameKnownAxesWithinRange) {
  EXPECT_THAT(ErrorOf("capture:\n  positions:\n    - {camera_arm: 10, tilt: 5}\n"),
              HasSubstr("no axis named 'tilt'"));
  EXPECT_THAT(ErrorOf("capture:\n  positions:\n    - {camera_arm: 95}\n"), HasSubstr(At(3) + ":"));
  const Scene scene = LoadSceneString(
      BaseSceneYaml() + "capture:\n  exposures: [0.01]\n  positions:\n    - {light_arm: -30}\n",
      "scene.yaml");
  EXPECT_NEAR(scene.capture.positions.at(0).at("light_arm"), -30 * kDegree, 1e-15);
}

TEST(SceneTest, FaultsAreCheckedToo) {
  EXPECT_THAT(ErrorOf("faults:\n  - {type: meteor}\n"), HasSubstr("unknown fault 'meteor'"));
  EXPECT_THAT(ErrorOf("faults:\n  - {type: axis_alarm, axis: tilt}\n"), HasSubstr(At(2) + ":"));
  EXPECT_THAT(ErrorOf("faults:\n  - {type: camera_disconnect}\n"),
              HasSubstr("missing required key 'after_shots'"));
  const Scene scene = LoadSceneString(BaseSceneYaml() + R"(faults:
  - {type: camera_disconnect, after_shots: 4, reopen_failures: 2}
  - {type: slow_download, at_shot: 2, duration_s: 30}
)",
                                      "scene.yaml");
  ASSERT_EQ(scene.faults.size(), 2u);
  EXPECT_EQ(scene.faults[0].at, 4);
  EXPECT_EQ(scene.faults[0].count, 2);
  EXPECT_DOUBLE_EQ(scene.faults[1].duration_s, 30);
}

TEST(SceneTest, CommandLinePositionsAreDegrees) {
  const geometry::AxisPositions p = ParsePositionsDegrees("camera_arm=15,light_arm=-15.5");
  EXPECT_NEAR(p.at("camera_arm"), 15 * kDegree, 1e-15);
  EXPECT_NEAR(p.at("light_arm"), -15.5 * kDegree, 1e-15);
  EXPECT_THROW(ParsePositionsDegrees("camera_arm=abc"), Error);
  EXPECT_THROW(ParsePositionsDegrees("camera_arm"), Error);
  EXPECT_THROW(ParsePositionsDegrees("a=1,a=2"), Error);
}

TEST(SceneTest, SampleCanBeAFittedSliceModelFile) {
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_sim_slices_scene";
  std::filesystem::create_directories(dir);
  brdf::Material material;
  brdf::Slice slice;
  slice.theta_in = 0.3;
  for (auto& lobe : slice.channel) lobe = {2.0, 0.1, 0.05, 0.2};
  material.slices = {slice};
  brdf::WriteMaterialFile(dir / "material.json", material);
  const Scene scene =
      LoadSceneString(BaseSceneYaml("{model: slices, file: material.json}"), "scene.yaml", dir);
  const geometry::Vec3 n = geometry::Vec3::UnitZ();
  const geometry::Vec3 l = geometry::Vec3(std::sin(0.3), 0, std::cos(0.3));
  const geometry::Vec3 mirror(-l.x(), 0, l.z());
  EXPECT_NEAR(scene.sample.brdf->Eval(l, mirror, n)[0], material.Model()->Eval(l, mirror, n)[0],
              1e-12);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace brdfrig::sim
