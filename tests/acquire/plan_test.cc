// Plans: parsing, presets, errors with file:line, and the dry run against the rig.
#include "acquire/plan.h"

#include <gtest/gtest.h>

#include "acquire/plan_check.h"
#include "common/error.h"
#include "tests/acquire/test_rig.h"

namespace brdfrig::acquire {
namespace {

constexpr double kDegree = M_PI / 180;

std::string ErrorOf(const std::string& text) {
  try {
    LoadPlanString(text, "plan.yaml");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

TEST(PlanTest, ExplicitPositionsAndBracketAreReadInRadians) {
  const Plan plan = LoadPlanString(testing::SmallPlanYaml(), "plan.yaml");
  ASSERT_EQ(plan.positions.size(), 3u);
  EXPECT_NEAR(plan.positions[1].axes.at("camera_arm"), 35 * kDegree, 1e-12);
  EXPECT_NEAR(plan.positions[1].axes.at("light_arm"), -35 * kDegree, 1e-12);
  EXPECT_EQ(plan.positions[1].line, 6);
  EXPECT_EQ(plan.exposures_s, (std::vector<double>{0.001, 0.01}));
  EXPECT_FALSE(plan.auto_bracket);
  EXPECT_EQ(plan.sample, "test-sample");
  EXPECT_EQ(plan.operator_name, "tester");
}

TEST(PlanTest, SymmetricArmsPresetSpreadsPositionsEvenly) {
  const Plan plan = LoadPlanString(
      "sample: s\npositions: {symmetric_arms: {from_deg: 20, to_deg: 60, count: 5}}\n", "p.yaml");
  ASSERT_EQ(plan.positions.size(), 5u);
  EXPECT_NEAR(plan.positions[2].axes.at("camera_arm"), 40 * kDegree, 1e-12);
  EXPECT_NEAR(plan.positions[2].axes.at("light_arm"), -40 * kDegree, 1e-12);
  // No exposures given: three, decided by metering.
  EXPECT_TRUE(plan.auto_bracket);
  EXPECT_EQ(plan.BracketSize(), 3);
}

TEST(PlanTest, AutoBracketingReadsTheSampleLevelAndTheLongestExposureAllowed) {
  const Plan plan = LoadPlanString(
      "sample: s\npositions:\n  - {camera_arm: 20}\n"
      "exposures: {auto: {count: 4, sample_level: 0.02, longest_max_s: 5}}\n",
      "plan.yaml");
  ASSERT_TRUE(plan.auto_bracket);
  EXPECT_EQ(plan.auto_settings.count, 4);
  EXPECT_DOUBLE_EQ(plan.auto_settings.sample_level, 0.02);
  EXPECT_DOUBLE_EQ(plan.auto_settings.longest_max_s, 5);
  // Defaults: the sample at ten times the reconstruction's noise floor, up to 30 s.
  const Plan defaults = LoadPlanString("sample: s\npositions:\n  - {camera_arm: 20}\n", "p.yaml");
  EXPECT_DOUBLE_EQ(defaults.auto_settings.sample_level, 0.01);
  EXPECT_DOUBLE_EQ(defaults.auto_settings.longest_max_s, 30);
  // A longest exposure shorter than the metering shot cannot be met: an error at its line.
  const std::string error = ErrorOf(
      "sample: s\npositions:\n  - {camera_arm: 20}\n"
      "exposures: {auto: {metering_s: 0.1, longest_max_s: 0.01}}\n");
  EXPECT_NE(error.find("plan.yaml:4:"), std::string::npos) << error;
  EXPECT_NE(error.find("longest_max_s"), std::string::npos) << error;
}

TEST(PlanTest, ErrorsNameFileAndLine) {
  EXPECT_NE(ErrorOf("sample: s\npositions:\n  - {camera_arm: 20}\nexposures: [0.01, -1]\n")
                .find("plan.yaml:4:"),
            std::string::npos);
  EXPECT_NE(ErrorOf("sample: s\npositions:\n  - {camera_arm: abc}\n").find("plan.yaml:3:"),
            std::string::npos);
  // An unknown key is an error, not silently ignored.
  EXPECT_NE(ErrorOf("sample: s\npositions:\n  - {camera_arm: 20}\nexposure: [0.01]\n")
                .find("plan.yaml:4:"),
            std::string::npos);
  EXPECT_NE(ErrorOf("sample: s\npositions: {symmetric_arms: {from_deg: 20, to_deg: 60, "
                    "count: 0}}\n")
                .find("plan.yaml:2:"),
            std::string::npos);
  EXPECT_NE(ErrorOf("positions:\n  - {camera_arm: 20}\n").find("sample"), std::string::npos);
  EXPECT_NE(ErrorOf("sample: s\npositions: []\n").find("plan.yaml:2:"), std::string::npos);
}

TEST(PlanCheckTest, GoodPlanIsReachableWithHighlightVisibleAndAnEstimate) {
  const auto rig = testing::MakeTestRig("plan_check_good");
  const Plan plan = LoadPlanFile(rig.plan_file);
  const PlanCheckReport report = CheckPlan(plan, rig::ReadRigDescription(rig.rig_file));
  EXPECT_TRUE(report.ok()) << report.ToString();
  ASSERT_EQ(report.positions.size(), 3u);
  for (const PositionCheck& c : report.positions) {
    EXPECT_TRUE(c.highlight_visible) << report.ToString();
    EXPECT_NEAR(c.highlight_x, 0, 1e-9);
  }
  EXPECT_NEAR(report.positions[1].theta_in, 35 * kDegree, 1e-6);
  // 3 positions x 2 shots: downloads 6 x 1.2 s (assumed), exposures (0.001 + 0.01 + 2 x 0.3) x 3.
  EXPECT_NEAR(report.downloads_s, 7.2, 1e-9);
  EXPECT_NEAR(report.exposures_s, 3 * (0.011 + 0.6), 1e-9);
  EXPECT_GT(report.moves_s, 0);
  EXPECT_NEAR(report.EstimatedDurationS(),
              report.moves_s + report.exposures_s + report.downloads_s + report.settle_s, 1e-12);
}

TEST(PlanCheckTest, LimitsUnknownAxesAndInvisibleHighlightAreReportedAtTheirLine) {
  const auto rig = testing::MakeTestRig("plan_check_bad");
  const Plan plan = LoadPlanString(R"(sample: s
positions:
  - {camera_arm: 20, light_arm: -20}
  - {camera_arm: 85, light_arm: -20}
  - {camera_arm: 20, tilt: 3}
  - {camera_arm: 30, light_arm: 10}
exposures: [0.01]
)",
                                   "bad.yaml");
  const PlanCheckReport report = CheckPlan(plan, rig::ReadRigDescription(rig.rig_file));
  EXPECT_FALSE(report.ok());
  ASSERT_EQ(report.errors.size(), 2u) << report.ToString();
  EXPECT_NE(report.errors[0].find("bad.yaml:4:"), std::string::npos) << report.errors[0];
  EXPECT_NE(report.errors[0].find("limits"), std::string::npos) << report.errors[0];
  EXPECT_NE(report.errors[1].find("bad.yaml:5:"), std::string::npos) << report.errors[1];
  EXPECT_NE(report.errors[1].find("tilt"), std::string::npos) << report.errors[1];
  // Camera and light on the same side: the mirror point is far off the cut-out.
  EXPECT_FALSE(report.positions[3].highlight_visible);
  ASSERT_EQ(report.warnings.size(), 1u) << report.ToString();
  EXPECT_NE(report.warnings[0].find("bad.yaml:6:"), std::string::npos);
}

}  // namespace
}  // namespace brdfrig::acquire

namespace brdfrig::acquire {
namespace {

// Found by fuzz_rig_yaml: a geometry file name the file system cannot look up (a component
// over 255 bytes) escaped as std::filesystem::filesystem_error instead of rig.yaml's error.
TEST(RigFileTest, UnlookableGeometryFileNameIsAFileErrorAtItsLine) {
  const auto rig = testing::MakeTestRig("rig_long_name");
  std::ofstream(rig.rig_file) << "geometry: " << std::string(300, 'g')
                              << ".yaml\ncamera: {backend: sim, scene: scene.yaml}\n";
  try {
    rig::ReadRigDescription(rig.rig_file);
    FAIL() << "an unlookable geometry file was accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.yaml:1:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("geometry file not found"), std::string::npos) << e.what();
  }
}

TEST(PlanDesignTest, DesignedPlanIsResolvedForTheRigAndExplained) {
  const auto rig = testing::MakeTestRig(
      "plan_design", "", "sample: s\npositions: {design: {count: 4, validation: 1}}\n");
  const Plan plan = LoadPlanFile(rig.plan_file);
  ASSERT_TRUE(plan.design.has_value());
  EXPECT_TRUE(plan.positions.empty());  // the rig decides them
  const geometry::RigDescription description = rig::ReadRigDescription(rig.rig_file);
  const PlanCheckReport report = CheckPlan(plan, description);
  ASSERT_TRUE(report.ok()) << report.ToString();
  ASSERT_EQ(report.resolved.size(), 5u);
  EXPECT_FALSE(report.resolved[3].validation);
  EXPECT_TRUE(report.resolved[4].validation);
  EXPECT_TRUE(report.has_coverage);
  EXPECT_GT(report.coverage.covered_fraction, 0);
  // Off-specular positions are intended: no "highlight not on the cut-out" warnings.
  EXPECT_TRUE(report.warnings.empty()) << report.ToString();
  const std::string text = report.ToString();
  EXPECT_NE(text.find("designed plan"), std::string::npos) << text;
  EXPECT_NE(text.find("covered fraction"), std::string::npos) << text;
  const std::string json = report.ToJson();
  EXPECT_NE(json.find("\"axes_deg\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"covered_fraction\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"validation\": true"), std::string::npos) << json;
  // ResolvePlan gives the positions CheckPlan checked.
  Plan resolved = plan;
  ResolvePlan(&resolved, description.geometry);
  ASSERT_EQ(resolved.positions.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(resolved.positions[i].axes, report.resolved[i].axes);
    EXPECT_EQ(resolved.positions[i].line, 2);
  }
}

TEST(PlanDesignTest, ExplicitValidationPositionsAndDesignErrors) {
  const Plan plan = LoadPlanString(
      "sample: s\npositions:\n  - {camera_arm: 20, light_arm: -20}\n"
      "  - {camera_arm: 30, light_arm: -10, validation: true}\n",
      "plan.yaml");
  ASSERT_EQ(plan.positions.size(), 2u);
  EXPECT_FALSE(plan.positions[0].validation);
  EXPECT_TRUE(plan.positions[1].validation);
  EXPECT_EQ(plan.positions[1].axes.count("validation"), 0u);
  EXPECT_NE(ErrorOf("sample: s\npositions: {design: {count: 30}}\n").find("plan.yaml:2:"),
            std::string::npos);
  EXPECT_NE(ErrorOf("sample: s\npositions: {design: {cout: 3}}\n").find("plan.yaml:2:"),
            std::string::npos);
}

}  // namespace
}  // namespace brdfrig::acquire
