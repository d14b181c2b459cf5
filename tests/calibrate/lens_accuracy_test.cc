// The lens calibration recovers the simulator's true camera from photos of the printed board
// (sim/scenes/charuco_board.yaml: 10 poses, 1600x1200, default sensor noise, a principal point
// off centre and k1 = -0.1): focal length within 0.2 %, principal point within 1 px, k1 within
// 0.01 (issue 24). A study in miniature: label `accuracy`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "calibrate/lens_calibration.h"
#include "sim/scene.h"
#include "sim/simulator.h"
#include "tests/calibrate/simulated_board_photos.h"

namespace brdfrig::calibrate {
namespace {

TEST(LensAccuracyTest, CalibrationRecoversTheSimulatorsTrueCamera) {
  const sim::Scene scene = sim::LoadScene(testing::ChArUcoScenePath());
  std::vector<int> poses;
  for (std::size_t i = 0; i < scene.board->world_from_page.size(); ++i) {
    poses.push_back(static_cast<int>(i));
  }
  LensCalibrationOptions options;
  options.board = scene.board->spec;
  const LensCalibrationResult result =
      CalibrateLens(testing::SimulatedBoardPhotos(scene, poses), options);
  const geometry::Intrinsics truth = sim::Simulator(scene).GeometryAt({}).intrinsics;
  const geometry::Intrinsics& k = result.calibration.intrinsics;
  std::printf("%s", result.ToString().c_str());
  std::printf("errors: fx %+.4f %%, fy %+.4f %%, cx %+.3f px, cy %+.3f px, k1 %+.5f, k2 %+.5f\n",
              100 * (k.fx / truth.fx - 1), 100 * (k.fy / truth.fy - 1), k.cx - truth.cx,
              k.cy - truth.cy, k.k1 - truth.k1, k.k2 - truth.k2);
  ASSERT_NE(truth.k1, 0) << "the scene must have a distorting lens for this test to mean much";
  EXPECT_LT(std::abs(k.fx / truth.fx - 1), 0.002);
  EXPECT_LT(std::abs(k.fy / truth.fy - 1), 0.002);
  EXPECT_LT(std::abs(k.cx - truth.cx), 1.0);
  EXPECT_LT(std::abs(k.cy - truth.cy), 1.0);
  EXPECT_LT(std::abs(k.k1 - truth.k1), 0.01);
  EXPECT_LT(result.calibration.rms_px, 0.2);
  EXPECT_EQ(result.calibration.photos.size(), poses.size());
}

}  // namespace
}  // namespace brdfrig::calibrate
