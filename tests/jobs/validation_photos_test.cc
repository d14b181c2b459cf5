// A capture's validation photos against a material (`brdfrig evaluate --capture`): the scene's
// own BRDF, written as a material, predicts its photos under the measured geometry; a wrong
// material does not; a capture without validation positions is a clear error.
#include "jobs/validation_photos.h"

#include <gtest/gtest.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/material_report.h"
#include "jobs/evaluate_job.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;
using reconstruct::testing::FlatSliceTruth;
using reconstruct::testing::SceneSpec;
using reconstruct::testing::SimulateCapture;

// Two fit positions and two validation positions: one on the highlight (mirror configuration)
// and one off it (the lobe's flank and floor); the default scene's sensor (14-bit, shot and
// read noise, saturation), so the truth scores what a real photo allows, not infinity.
SceneSpec SmallSpec(bool with_validation) {
  SceneSpec spec;
  spec.width = 320;
  spec.height = 240;
  spec.supersampling = 4;
  spec.effects =
      "[{type: shot_noise, full_well: 30000}, {type: read_noise, sigma: 0.0005}, "
      "{type: saturation, level: 1.0}, {type: quantization, bits: 14}]";
  spec.positions =
      "[{camera_arm: 20, light_arm: -20}, {camera_arm: 50, light_arm: -50}" +
      std::string(with_validation ? ", {camera_arm: 35, light_arm: -35, validation: true}, "
                                    "{camera_arm: 30, light_arm: -22, validation: true}]"
                                  : "]");
  return spec;
}

brdf::Material WrongMaterial() {
  brdf::Material m = FlatSliceTruth();
  for (brdf::LobeParams& p : m.slices[0].channel) {
    p.a1 *= 0.5;
    p.a2 *= 2;  // the off-specular validation photo sees mostly the floor
    p.x0 *= 1.6;
  }
  return m;
}

double MeanPsnr(const std::vector<evaluate::ValidationPhotoResult>& results) {
  double sum = 0;
  for (const auto& r : results) sum += r.figures.normalized_sample.psnr_db;
  return sum / static_cast<double>(results.size());
}

TEST(ValidationPhotosTest, TheTruthPredictsItsPhotosAndAWrongMaterialDoesNot) {
  const brdf::Material truth = FlatSliceTruth();
  const reconstruct::CaptureSet capture = SimulateCapture(
      fs::temp_directory_path() / "brdfrig_validation_photos", SmallSpec(true), &truth);
  // The light refined with the lobe: the truth is a slice model, symmetric about the mirror
  // direction, the refinement's premise (reconstruct/light_refine.h). The highlight's centroid
  // alone is off by tenths of a degree here, which costs the off-highlight photo's prediction
  // about half a percent of relative RMSE.
  ValidationPhotoOptions options;
  options.measure.light_refine.enabled = true;
  const auto truth_results = CompareValidationPhotos(capture, *truth.Model(), options);
  ASSERT_EQ(truth_results.size(), 2u);
  EXPECT_EQ(truth_results[0].position, 2);
  EXPECT_EQ(truth_results[1].position, 3);
  const auto wrong_results = CompareValidationPhotos(capture, *WrongMaterial().Model(), options);
  ASSERT_EQ(wrong_results.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& t = truth_results[i];
    const auto& w = wrong_results[i];
    ASSERT_TRUE(t.measured) << t.error;
    ASSERT_TRUE(w.measured) << w.error;
    std::printf("position %d: truth %.2f dB (relative RMSE %.4f), wrong %.2f dB (%.4f), %ld px\n",
                t.position, t.figures.normalized_sample.psnr_db, t.figures.relative_rmse,
                w.figures.normalized_sample.psnr_db, w.figures.relative_rmse,
                t.figures.normalized_sample.pixels);
    EXPECT_GT(t.figures.normalized_sample.psnr_db, 35) << "position " << t.position;
    EXPECT_LT(t.figures.relative_rmse, 0.05) << "position " << t.position;
    EXPECT_LT(w.figures.normalized_sample.psnr_db, t.figures.normalized_sample.psnr_db - 10)
        << "position " << t.position;
    EXPECT_GT(w.figures.relative_rmse, 3 * t.figures.relative_rmse);
    EXPECT_GT(t.figures.normalized_sample.pixels, 1000);
    EXPECT_NE(t.figures.normalized_sample.protocol.find("photo's 99th percentile"),
              std::string::npos);
    EXPECT_FALSE(t.photo.empty());
    EXPECT_EQ(t.photo.size(), t.prediction.size());
  }
  EXPECT_GT(MeanPsnr(truth_results), MeanPsnr(wrong_results) + 10);
}

TEST(ValidationPhotosTest, EvaluateWritesTheComparisonIntoTheReport) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_validation_report";
  const brdf::Material truth = FlatSliceTruth();
  (void)SimulateCapture(dir, SmallSpec(true), &truth);
  EvaluateOptions options;
  options.material = dir / "truth.json";
  options.capture = dir / "capture";
  options.output_dir = dir / "report";
  const EvaluateSummary summary = RunEvaluate(options);
  const nlohmann::json report = nlohmann::json::parse(ReadFileToString(summary.report_json));
  const nlohmann::json& v = report.at("figures").at("validation_photos");
  ASSERT_EQ(v.at("positions").size(), 2u);
  EXPECT_GT(evaluate::NumberFromJson(v.at("mean_normalized_sample_psnr_db")), 35);
  EXPECT_NE(v.at("protocols").at("normalized_sample_psnr_db").get<std::string>().find("photo"),
            std::string::npos);
  EXPECT_FALSE(report.at("figures").contains("held_out")) << "no scene was given";
  EXPECT_TRUE(fs::exists(dir / "report" / "validation" / "p2_diff.png"));
  EXPECT_NE(summary.text.find("Validation photos"), std::string::npos);
  EXPECT_NE(summary.text.find("photo's 99th percentile"), std::string::npos);
  EXPECT_EQ(ReadFileToString(dir / "report" / "report.txt"), summary.text);

  // Named positions instead of the plan's: a fit position, compared all the same.
  options.positions = {1};
  options.output_dir = dir / "report_p1";
  const nlohmann::json named =
      nlohmann::json::parse(ReadFileToString(RunEvaluate(options).report_json));
  ASSERT_EQ(named["figures"]["validation_photos"]["positions"].size(), 1u);
  EXPECT_EQ(named["figures"]["validation_photos"]["positions"][0]["position"].get<int>(), 1);
}

TEST(ValidationPhotosTest, ACaptureWithoutValidationPositionsIsAClearError) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_validation_none";
  const brdf::Material truth = FlatSliceTruth();
  const reconstruct::CaptureSet capture = SimulateCapture(dir, SmallSpec(false), &truth);
  try {
    (void)CompareValidationPhotos(capture, *truth.Model(), {});
    FAIL() << "compared a capture that has no validation positions";
  } catch (const OptionsError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no validation positions"), std::string::npos) << what;
    EXPECT_NE(what.find("--positions"), std::string::npos) << what;
    EXPECT_NE(what.find(capture.name), std::string::npos) << what;
  }
  ValidationPhotoOptions options;
  options.positions = {7};
  try {
    (void)CompareValidationPhotos(capture, *truth.Model(), options);
    FAIL() << "compared a position the capture does not have";
  } catch (const OptionsError& e) {
    EXPECT_NE(std::string(e.what()).find("position 7 is not in the capture (its positions: 0, 1)"),
              std::string::npos)
        << e.what();
  }
  // Through the job: the error comes before any report file is written.
  EvaluateOptions job;
  job.material = dir / "truth.json";
  job.capture = dir / "capture";
  job.output_dir = dir / "report";
  EXPECT_THROW(RunEvaluate(job), OptionsError);
  EXPECT_FALSE(fs::exists(dir / "report"));
}

}  // namespace
}  // namespace brdfrig::jobs
