// The quick subset of the hemisphere study (ctest label "study"): the instruments on one
// analytic material. A perfect fit scores at the ceiling; the seed's fit from today's
// mirror-only plan scores clearly lower away from the photographed configurations.
#include <gtest/gtest.h>

#include <cmath>

#include "brdf/analytic.h"
#include "jobs/material_study.h"
#include "sim/scene.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

evaluate::JudgeOptions QuickJudge() {
  evaluate::JudgeOptions judge;
  judge.view_elevations_deg = {20, 75};
  judge.view_phis_deg = {0, 180};
  judge.sphere.resolution = 64;
  return judge;
}

const char* kMaterial =
    "{model: ggx, alpha: 0.2, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}";

TEST(StudyQuickTest, PerfectFitScoresAtTheCeilingAndTheSeedFitClearlyLowerOffSpecular) {
  // Perfect fit: the truth judged against itself through the same instruments.
  sim::Scene scene = sim::LoadScene(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/ggx.yaml");
  geometry::Intrinsics& k = scene.rig.intrinsics;
  const double scale = 320.0 / k.width;
  k = {320, 240, k.fx * scale, k.fy * scale, 160, 120};
  scene.render.supersampling = 1;
  scene.sample.brdf = std::make_shared<brdf::Ggx>(
      brdf::MicrofacetParams{brdf::Rgb(0.1, 0.05, 0.03), brdf::Rgb(0.9, 0.6, 0.35), 0.2});
  const evaluate::MaterialFigures perfect =
      evaluate::JudgeFit(scene, *scene.sample.brdf, QuickJudge());
  EXPECT_TRUE(std::isinf(perfect.sphere.mean_psnr_db)) << perfect.sphere.Report();
  EXPECT_NEAR(perfect.brdf.max_albedo_error, 0, 1e-9);
  ASSERT_EQ(perfect.held_out.size(), 4u);
  for (const evaluate::HeldOutResult& v : perfect.held_out) {
    // Only the GPU's float rendering separates the two radiance images.
    EXPECT_GT(v.normalized_sample.psnr_db, 40) << v.view.name;
    EXPECT_LT(v.relative_rmse, 0.02) << v.view.name;
  }

  // The seed's fit from the mirror plan, through the study harness.
  MaterialStudyOptions options;
  options.width = 400;
  options.height = 300;
  options.judge = QuickJudge();
  options.work_dir = fs::temp_directory_path() / "brdfrig_study_quick";
  options.model = "seed";
  const MaterialStudyRow row = RunMaterialStudyPoint({"GGX 0.2", kMaterial}, MirrorPlan(), options);
  ASSERT_TRUE(row.error.empty()) << row.error;
  const evaluate::MaterialFigures& seed = row.result.figures;
  ASSERT_EQ(seed.held_out.size(), 4u);
  ASSERT_EQ(seed.sphere.lights.size(), 4u);
  EXPECT_LT(row.sphere_mean_db, 35) << seed.sphere.Report();
  EXPECT_LT(row.sphere_worst_db, row.sphere_mean_db + 1e-9);
  // Off-specular (light turned 180° about the normal, on the camera's side), the seed's
  // extrapolated lobe is far from the truth.
  double worst_seed = INFINITY;
  for (const evaluate::HeldOutResult& v : seed.held_out) {
    worst_seed = std::min(worst_seed, v.normalized_sample.psnr_db);
  }
  EXPECT_LT(worst_seed, 30) << row.Report();
  EXPECT_GT(row.result.reconstruct_time_s, 0);
  std::string warnings;
  for (const auto& w : row.result.warnings) warnings += w + "\n";
  EXPECT_EQ(row.result.slices, 6) << warnings;
  EXPECT_FALSE(fs::exists(options.work_dir));
  const std::string table = MarkdownTable({row}, MirrorPlan());
  EXPECT_NE(table.find("| GGX 0.2 |"), std::string::npos) << table;
  EXPECT_NE(table.find("sphere 80°"), std::string::npos) << table;
  EXPECT_NE(table.find("held-out el 75°"), std::string::npos) << table;
}

}  // namespace
}  // namespace brdfrig::jobs
