// `brdfrig evaluate` as a library call: a material judged against a small simulated scene.
#include "jobs/evaluate_job.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <regex>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "evaluate/material_report.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

// The default scene at 320×240 (same field of view), written next to the test's files.
fs::path SmallScene(const fs::path& dir) {
  std::string text = ReadFileToString(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/ggx.yaml");
  text = std::regex_replace(text, std::regex("resolution: \\[1600, 1200\\]"),
                            "resolution: [320, 240]");
  fs::create_directories(dir);
  WriteFileAtomically(dir / "scene.yaml", text);
  return dir / "scene.yaml";
}

TEST(EvaluateJobTest, WritesAReportWithBothPsnrsAndTheBrdfError) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_evaluate_job";
  fs::remove_all(dir);
  EvaluateOptions options;
  options.material = fs::path(BRDFRIG_SOURCE_DIR) / "tests/data/glossy_slices.json";
  options.scene = SmallScene(dir);
  options.output_dir = dir / "report";
  options.view_elevations_deg = {40, 75};
  options.view_phis_deg = {0, 90};
  const EvaluateSummary summary = RunEvaluate(options);
  // The figures decode, pair up in size, and show the difference a wrong material makes.
  const fs::path views_dir = dir / "report" / "views", spheres_dir = dir / "report" / "spheres";
  const cv::Mat photo = cv::imread((views_dir / "el40_phi90_photo.png").string());
  const cv::Mat rendering = cv::imread((views_dir / "el40_phi90_render.png").string());
  const cv::Mat diff = cv::imread((views_dir / "el40_phi90_diff.png").string());
  ASSERT_FALSE(photo.empty());
  EXPECT_EQ(rendering.size(), photo.size());
  EXPECT_EQ(diff.size(), photo.size());
  EXPECT_GT(cv::norm(photo, rendering, cv::NORM_L1), 0);
  const cv::Mat truth = cv::imread((spheres_dir / "light80_truth.png").string());
  const cv::Mat fit = cv::imread((spheres_dir / "light80_fit.png").string());
  ASSERT_FALSE(truth.empty());
  ASSERT_EQ(fit.size(), truth.size());
  EXPECT_GT(cv::norm(truth, fit, cv::NORM_L1), 0);
  // The page shows them.
  const std::string html = ReadFileToString(summary.report_html);
  EXPECT_NE(html.find("el40_phi90_diff.png"), std::string::npos);
  EXPECT_NE(html.find("light80_fit.png"), std::string::npos);
  EXPECT_NE(summary.text.find("whole photo"), std::string::npos);
  EXPECT_NE(summary.text.find("sample only"), std::string::npos);
  EXPECT_NE(summary.text.find("Log-cosine error"), std::string::npos);
  EXPECT_NE(summary.text.find("Sphere test"), std::string::npos);
  EXPECT_NE(summary.text.find("normalized sample"), std::string::npos);
  // report.json holds every figure; the text is generated from it.
  const nlohmann::json report = nlohmann::json::parse(ReadFileToString(summary.report_json));
  const nlohmann::json& views = report.at("figures").at("held_out").at("views");
  ASSERT_EQ(views.size(), 4u);
  EXPECT_DOUBLE_EQ(views[3].at("elevation_deg").get<double>(), 75);
  EXPECT_DOUBLE_EQ(views[3].at("phi_deg").get<double>(), 90);
  for (const auto& v : views) {
    // A slice file fitted to another material: far from the default scene's GGX.
    EXPECT_LT(evaluate::NumberFromJson(v.at("normalized_sample_psnr_db")), 40) << v.dump();
    EXPECT_GT(evaluate::NumberFromJson(v.at("relative_rmse")), 0.01) << v.dump();
  }
  const nlohmann::json& sphere = report["figures"].at("sphere");
  EXPECT_EQ(sphere.at("lights").size(), 4u);
  EXPECT_NE(summary.text.find(Fixed(evaluate::NumberFromJson(sphere["mean_psnr_db"]), 2)),
            std::string::npos);
  EXPECT_EQ(report["figures"].at("brdf").at("albedo").size(), 7u);
  EXPECT_EQ(ReadFileToString(dir / "report" / "report.txt"), summary.text);
}

TEST(EvaluateJobTest, MalformedMaterialIsAFileErrorNamingIt) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_evaluate_job_bad";
  fs::create_directories(dir);
  WriteFileAtomically(dir / "material.json", "{\"format\": \"brdfrig-slices\", \"version\": 1");
  EvaluateOptions options;
  options.material = dir / "material.json";
  options.scene = SmallScene(dir);
  options.output_dir = dir / "report";
  try {
    RunEvaluate(options);
    FAIL() << "a truncated material was evaluated";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("material.json"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "report" / "report.html"));
}

}  // namespace
}  // namespace brdfrig::jobs
