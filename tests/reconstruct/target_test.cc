// The cut-out's corners and the camera pose, measured on simulated radiance against the truth.
#include "reconstruct/target.h"

#include <gtest/gtest.h>

#include "sim/scene.h"
#include "sim/simulator.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

constexpr double kDeg = M_PI / 180;

sim::Simulator MakeSimulator(const testing::SceneSpec& spec) {
  return sim::Simulator(sim::LoadSceneString(testing::SceneYaml(spec), "scene.yaml"));
}

class TargetTest : public ::testing::TestWithParam<double> {};

TEST_P(TargetTest, CornersAndPoseMatchTheTruth) {
  testing::SceneSpec spec;
  spec.brdf = "{model: ggx, alpha: 0.1, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}";
  const sim::Simulator simulator = MakeSimulator(spec);
  const geometry::RigGeometry& rig = simulator.scene().rig;
  const geometry::AxisPositions at = {{"camera_arm", GetParam() * kDeg},
                                      {"light_arm", -GetParam() * kDeg}};
  const cv::Mat radiance = simulator.RenderRadiance(at);
  const cv::Mat valid(radiance.size(), CV_8U, cv::Scalar(255));
  const geometry::CameraPose truth = rig.CameraAt(at);
  // Start from a nominal pose 5 mm and half a degree off, as a real rig would be.
  geometry::CameraPose nominal = truth;
  nominal.camera_from_world.translate(geometry::Vec3(0.005, -0.003, 0.002));
  nominal.camera_from_world.rotate(Eigen::AngleAxisd(0.5 * kDeg, geometry::Vec3::UnitX()));
  const TargetOptions options;
  const TargetCorners corners =
      FindCutoutCorners(radiance, valid, rig.intrinsics, nominal, rig.target, options);
  const double w = rig.target.cutout_width / 2, h = rig.target.cutout_height / 2;
  const geometry::Vec3 world[4] = {{-w, -h, 0}, {w, -h, 0}, {w, h, 0}, {-w, h, 0}};
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector2d want;
    ASSERT_TRUE(geometry::ProjectToPixel(rig.intrinsics, truth, world[k], &want));
    EXPECT_NEAR(corners.corners[k].x, want.x(), 0.05) << "corner " << k;
    EXPECT_NEAR(corners.corners[k].y, want.y(), 0.05) << "corner " << k;
  }
  const PoseEstimate pose = EstimatePose(corners, rig.intrinsics, rig.target, nominal, options);
  EXPECT_LT((pose.pose.CenterInWorld() - truth.CenterInWorld()).norm(), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(CameraAngles, TargetTest, ::testing::Values(20.0, 40.0, 60.0));

}  // namespace
}  // namespace brdfrig::reconstruct
