// `brdfrig evaluate` as a library call: a material judged against a small simulated scene.
#include "jobs/evaluate_job.h"

#include <gtest/gtest.h>

#include <regex>

#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

// The default scene at 320×240 (same field of view), written next to the test's files.
fs::path SmallScene(const fs::path& dir) {
  std::string text = ReadFileToString(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml");
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
  options.view_phis_deg = {0, 90};
  const EvaluateSummary summary = RunEvaluate(options);
  EXPECT_TRUE(fs::exists(summary.report_html));
  EXPECT_TRUE(fs::exists(dir / "report" / "report.txt"));
  EXPECT_TRUE(fs::exists(dir / "report" / "views" / "phi90_diff.png"));
  EXPECT_NE(summary.text.find("whole photo"), std::string::npos);
  EXPECT_NE(summary.text.find("sample only"), std::string::npos);
  EXPECT_NE(summary.text.find("Log-cosine error"), std::string::npos);
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
