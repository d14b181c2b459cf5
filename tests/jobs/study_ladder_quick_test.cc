// The hemisphere study's rung side-by-side harness on one analytic material at a small
// resolution (ctest label "study"): one capture and one reconstruction, every rung of the
// ladder judged with the same figures.
#include <gtest/gtest.h>

#include <cmath>

#include "brdf/material_file.h"
#include "evaluate/sphere_test.h"
#include "jobs/material_study.h"
#include "jobs/study.h"

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

// Every rung of the ladder judged side by side from one capture and one reconstruction on a
// designed plan: each fitted rung has every figure, validation's choice is the row's headline
// and the best rung is the one with the highest sphere mean.
TEST(StudyQuickTest, EveryRungJudgedSideBySideOnADesignedPlan) {
  MaterialStudyOptions options;
  options.width = 320;
  options.height = 240;
  options.judge = QuickJudge();
  options.every_rung = true;
  options.work_dir = fs::temp_directory_path() / "brdfrig_study_ladder_quick";
  options.keep_materials_dir = fs::temp_directory_path() / "brdfrig_study_ladder_quick_kept";
  fs::remove_all(options.keep_materials_dir);
  const StudyPlan plan = DesignedPlan(6);
  ASSERT_EQ(plan.positions.size(), 6u);
  const MaterialStudyRow row = RunMaterialStudyPoint({"GGX 0.2", kMaterial}, plan, options);
  ASSERT_TRUE(row.error.empty()) << row.error;
  EXPECT_FALSE(fs::exists(options.work_dir));
  ASSERT_EQ(row.rungs.size(), std::size(brdf::kLadderModelKinds)) << row.Report();
  ASSERT_GE(row.chosen, 0);
  ASSERT_GE(row.best, 0);
  int chosen = 0;
  for (const RungRow& r : row.rungs) {
    chosen += r.chosen;
    if (!r.fitted) continue;
    EXPECT_GT(r.size_bytes, 0u) << r.kind;
    EXPECT_TRUE(std::isfinite(r.held_out_mean_db)) << r.kind;
    EXPECT_LE(r.held_out_min_db, r.held_out_mean_db + 1e-9) << r.kind;
    EXPECT_LE(r.sphere_worst_db, r.sphere_mean_db + 1e-9) << r.kind;
    EXPECT_LE(r.sphere_mean_db, row.rungs[row.best].sphere_mean_db) << r.kind;
  }
  EXPECT_EQ(chosen, 1);
  EXPECT_EQ(row.result.rungs.size(), std::size(brdf::kLadderModelKinds));
  EXPECT_EQ(row.result.rungs[row.chosen].figures.held_out.size(), 4u);
  EXPECT_DOUBLE_EQ(row.sphere_mean_db, row.rungs[row.chosen].sphere_mean_db);
  // A microfacet rung fits a GGX truth far better than the seed's slices on the sphere.
  EXPECT_GT(row.rungs[row.best].sphere_mean_db, row.rungs[0].sphere_mean_db) << row.Report();
  const std::string table = LadderMarkdown({row}, plan, 0.05);
  EXPECT_NE(table.find("(chosen)"), std::string::npos) << table;
  EXPECT_NE(table.find("best by sphere"), std::string::npos) << table;
  EXPECT_NE(table.find("| ggx"), std::string::npos) << table;

  // The written material is kept with its glTF version, and that glTF version is judged on the
  // same sphere test against the truth as the rung.
  const fs::path kept = options.keep_materials_dir / "GGX_0.2.json";
  ASSERT_TRUE(fs::exists(kept));
  const brdf::Material material = brdf::ReadMaterialFile(kept);
  EXPECT_EQ(material.kind, row.result.material.kind);
  ASSERT_TRUE(material.gltf.has_value()) << "reconstruct writes the chosen rung's glTF version";
  StudySettings truth_settings;
  truth_settings.sample_brdf = kMaterial;
  const sim::Scene truth =
      StudyScene(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml", truth_settings);
  const evaluate::SphereTestResult expected = evaluate::SphereTest(
      *truth.sample.brdf, brdf::GltfModel(*material.gltf), QuickJudge().sphere);
  EXPECT_NEAR(row.gltf_sphere_mean_db, expected.mean_psnr_db, 1e-6);
  EXPECT_NEAR(row.gltf_sphere_worst_db, expected.worst_psnr_db, 1e-6);
  EXPECT_TRUE(std::isfinite(row.gltf_vs_rung_db)) << material.gltf_fit.dump();
  const std::string gltf_table = GltfMarkdown({row});
  EXPECT_NE(gltf_table.find("| GGX 0.2 | " + std::string(brdf::ModelKindName(material.kind))),
            std::string::npos)
      << gltf_table;
  fs::remove_all(options.keep_materials_dir);
}

}  // namespace
}  // namespace brdfrig::jobs
