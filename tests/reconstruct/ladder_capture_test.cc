// End to end on a simulated capture with off-specular positions: the rung chosen by validation
// is far closer to the truth than the seed.
#include <gtest/gtest.h>

#include "brdf/metrics.h"
#include "reconstruct/energy.h"
#include "reconstruct/pipeline.h"
#include "sim/scene.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

TEST(LadderCaptureTest, ChosenRungBeatsTheSeedByFarOnADesignedPlan) {
  testing::SceneSpec spec;
  spec.brdf = "{model: ggx, alpha: 0.1, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}";
  // Mirror at 15° and 45°; theta_h ≈ 10°, 25°, 45°; the light 90° out of the camera's plane.
  spec.positions =
      "[{camera_arm: 15, light_arm: -15}, {camera_arm: 45, light_arm: -45}, "
      "{camera_arm: 35, light_arm: -15}, {camera_arm: 60, light_arm: -10}, "
      "{camera_arm: 70, light_arm: 20}, {camera_arm: 30, light_arm: -30, light_azimuth: 90}]";
  spec.supersampling = 4;
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_reconstruct_ladder";
  const CaptureSet capture = testing::SimulateCapture(dir, spec);
  const ReconstructionResult result = Reconstruct(capture, ReconstructOptions{});
  std::cout << result.Summary();
  const sim::Scene scene = sim::LoadScene(dir / "scene.yaml");
  const brdf::Brdf& truth = *scene.sample.brdf;
  double seed_error = 0;
  for (const RungResult& r : result.ladder.rungs) {
    if (!r.fitted) continue;
    const double e = brdf::LogCosineError(truth, *r.material.Model());
    std::cout << brdf::ModelKindName(r.kind) << ": BRDF error " << e << "\n";
    if (r.kind == brdf::ModelKind::kSeed) seed_error = e;
  }
  ASSERT_GT(seed_error, 0);
  EXPECT_FALSE(brdf::IsSliceKind(result.material.kind));
  const double chosen_error = brdf::LogCosineError(truth, *result.material.Model());
  EXPECT_LT(chosen_error, 0.25 * seed_error);
  EXPECT_LE(MaxAlbedo(*result.material.Model()).albedo, 1.0);
}

}  // namespace
}  // namespace brdfrig::reconstruct
