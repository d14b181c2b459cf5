#include "evaluate/held_out.h"

#include <gtest/gtest.h>

#include "brdf/analytic.h"
#include "sim/scene.h"

namespace brdfrig::evaluate {
namespace {

sim::Scene SmallScene() {
  sim::Scene scene = sim::LoadScene(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/ggx.yaml");
  geometry::Intrinsics& k = scene.rig.intrinsics;
  const double scale = 320.0 / k.width;
  k = {320,          static_cast<int>(k.height * scale),
       k.fx * scale, k.fy * scale,
       160,          k.height * scale / 2};
  return scene;
}

TEST(HeldOutTest, TrueMaterialScoresAtTheNoiseFloorAndAWrongOneScoresLower) {
  const sim::Scene scene = SmallScene();
  const auto views = OrientationViews(40 * M_PI / 180, {0.0, 0.5});
  const auto truth = EvaluateHeldOut(scene, *scene.sample.brdf, views);
  const brdf::Ggx wrong({brdf::Rgb(0.1, 0.05, 0.03), brdf::Rgb(0.9, 0.6, 0.35), 0.2});
  const auto bad = EvaluateHeldOut(scene, wrong, views);
  ASSERT_EQ(truth.size(), 2u);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    // Only sensor noise separates the photo from the true material's rendering.
    EXPECT_GT(truth[i].whole_photo.psnr_db, 45) << truth[i].whole_photo.Report();
    EXPECT_GT(truth[i].sample_only.psnr_db, 40) << truth[i].sample_only.Report();
    EXPECT_LT(bad[i].sample_only.psnr_db, truth[i].sample_only.psnr_db - 5);
    // The paper dominates the whole photo: its PSNR flatters the wrong material.
    EXPECT_GT(bad[i].whole_photo.psnr_db, bad[i].sample_only.psnr_db);
    EXPECT_NE(truth[i].whole_photo.protocol.find("whole photo"), std::string::npos);
    EXPECT_NE(truth[i].sample_only.protocol.find("sample only, 14-bit"), std::string::npos);
    // Exposure independent figures on radiance: the truth is at the rendering's float floor.
    EXPECT_GT(truth[i].normalized_sample.psnr_db, 40) << truth[i].normalized_sample.Report();
    EXPECT_LT(truth[i].relative_rmse, 0.02);
    EXPECT_LT(bad[i].normalized_sample.psnr_db, truth[i].normalized_sample.psnr_db - 10);
    EXPECT_GT(bad[i].relative_rmse, 0.1);
    EXPECT_NE(truth[i].normalized_sample.protocol.find("99th percentile"), std::string::npos);
    EXPECT_NE(truth[i].relative_rmse_protocol.find("linear radiance"), std::string::npos);
  }
}

TEST(HeldOutTest, ElevationViewsCoverEveryElevationAndAzimuth) {
  const auto views = ElevationViews({20 * M_PI / 180, 75 * M_PI / 180}, {0.0, M_PI});
  ASSERT_EQ(views.size(), 4u);
  EXPECT_EQ(views[3].name, "el=75deg phi=180deg");
  EXPECT_DOUBLE_EQ(views[3].elevation, 75 * M_PI / 180);
  EXPECT_DOUBLE_EQ(views[3].positions.at("camera_arm"), 75 * M_PI / 180);
  EXPECT_DOUBLE_EQ(views[3].positions.at("light_arm"), -75 * M_PI / 180);
  EXPECT_DOUBLE_EQ(views[3].positions.at("light_azimuth"), M_PI);
}

}  // namespace
}  // namespace brdfrig::evaluate
