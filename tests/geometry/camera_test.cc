#include "geometry/camera.h"

#include <gtest/gtest.h>

namespace brdfrig::geometry {
namespace {

TEST(LookAtTest, TargetProjectsToPrincipalPointAndUpIsUpInTheImage) {
  const Intrinsics k{640, 480, 500, 500, 320, 240};
  const CameraPose pose = LookAt({0.1, -0.3, 0.4}, {0, 0, 0}, Vec3::UnitZ());
  EXPECT_NEAR((pose.CenterInWorld() - Vec3(0.1, -0.3, 0.4)).norm(), 0, 1e-12);
  Eigen::Vector2d centre, above;
  ASSERT_TRUE(ProjectToPixel(k, pose, Vec3::Zero(), &centre));
  EXPECT_NEAR(centre.x(), 320, 1e-9);
  EXPECT_NEAR(centre.y(), 240, 1e-9);
  ASSERT_TRUE(ProjectToPixel(k, pose, Vec3(0, 0, 0.01), &above));
  EXPECT_LT(above.y(), centre.y());  // image y points down: world up appears above the centre
}

TEST(LookAtTest, IsTheInverseOfWorldFromCamera) {
  const Vec3 eye(0.2, 0.1, 0.5), target(0.01, -0.02, 0), up(0, 1, 0);
  const Eigen::Isometry3d product =
      LookAt(eye, target, up).camera_from_world * WorldFromCameraLookingAt(eye, target, up);
  EXPECT_TRUE(product.matrix().isApprox(Eigen::Matrix4d::Identity(), 1e-12));
}

TEST(PixelRayTest, RayThroughProjectionHitsThePoint) {
  const Intrinsics k{800, 600, 700, 710, 400, 300, -0.05, 0.01};
  const CameraPose pose = LookAt({0, -0.4, 0.4}, {0, 0, 0}, Vec3::UnitZ());
  const Vec3 x(0.03, -0.02, 0);
  Eigen::Vector2d pixel;
  ASSERT_TRUE(ProjectToPixel(k, pose, x, &pixel));
  const Vec3 ray = PixelRayInWorld(k, pose, pixel);
  const Vec3 to_x = (x - pose.CenterInWorld()).normalized();
  EXPECT_NEAR((ray - to_x).norm(), 0, 1e-9);
}

}  // namespace
}  // namespace brdfrig::geometry
