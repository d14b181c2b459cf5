#include "geometry/rig_geometry.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace brdfrig::geometry {
namespace {

constexpr char kRig[] = R"(geometry:
  camera:
    resolution: [800, 600]
    focal_length_mm: 50
    sensor_width_mm: 36
    distortion: [-0.05, 0.01]
    position: [0, -0.4, 0.4]
    look_at: [0, 0, 0]
  light:
    position: [0, 0.4, 0.4]
    intensity: 2.5
  axes:
    - {name: camera_arm, moves: camera, direction: [1, 0, 0], range_deg: [-60, 60]}
    - {name: light_arm, moves: light, direction: [1, 0, 0], range_deg: [-60, 60]}
    - {name: tilt, moves: sample, direction: [1, 0, 0], range_deg: [-30, 30]}
  target:
    cutout: [0.1, 0.08]
    paper: [0.3, 0.3]
    paper_albedo: 0.75
)";

RigGeometry Parse(const std::string& text) {
  return ParseRigGeometry(LoadYamlString(text, "rig.yaml").Required("geometry"));
}

// What parsing `text` reports: the FileError's message, "" when it parses.
std::string ParseError(const std::string& text) {
  try {
    Parse(text);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

TEST(RigGeometryTest, ParsesEverySection) {
  const RigGeometry rig = Parse(kRig);
  EXPECT_EQ(rig.intrinsics.width, 800);
  EXPECT_NEAR(rig.intrinsics.fx, 50.0 / 36.0 * 800, 1e-9);
  EXPECT_DOUBLE_EQ(rig.light_intensity, 2.5);
  ASSERT_EQ(rig.axes.size(), 3u);
  EXPECT_NEAR(rig.axes[0].max, M_PI / 3, 1e-12);
  EXPECT_DOUBLE_EQ(rig.target.cutout_height, 0.08);
  EXPECT_DOUBLE_EQ(rig.target.paper_albedo, 0.75);
  EXPECT_FALSE(rig.target.markers) << "a plain mask unless the rig says otherwise";
}

TEST(RigGeometryTest, TargetMarkersDescribeTheMarkerMaskAndRefuseUnknownKeysAtTheirLine) {
  std::string defaults = kRig;
  defaults += "    markers: {}\n";
  const RigGeometry plain_ring = Parse(defaults);
  ASSERT_TRUE(plain_ring.target.markers);
  EXPECT_DOUBLE_EQ(plain_ring.target.markers->marker, 0.02);
  EXPECT_DOUBLE_EQ(plain_ring.target.markers->gap, 0.01);
  EXPECT_EQ(plain_ring.target.markers->dictionary, "DICT_4X4_100");

  std::string custom = kRig;
  custom +=
      "    markers: {size: 0.015, gap: 0.008, spacing: 0.006, dictionary: DICT_5X5_100, "
      "first_id: 7}\n";
  const RigGeometry ring = Parse(custom);
  ASSERT_TRUE(ring.target.markers);
  EXPECT_DOUBLE_EQ(ring.target.markers->marker, 0.015);
  EXPECT_DOUBLE_EQ(ring.target.markers->gap, 0.008);
  EXPECT_DOUBLE_EQ(ring.target.markers->spacing, 0.006);
  EXPECT_EQ(ring.target.markers->dictionary, "DICT_5X5_100");
  EXPECT_EQ(ring.target.markers->first_id, 7);

  std::string typo = kRig;
  typo += "    markers: {sise: 0.02}\n";
  EXPECT_THAT(ParseError(typo), ::testing::HasSubstr("rig.yaml:20:15: unknown key"));
  std::string negative = kRig;
  negative += "    markers: {gap: -0.01}\n";
  EXPECT_THROW(Parse(negative), FileError);
}

TEST(RigGeometryTest, RestCameraSeesLookAtPointAtPrincipalPoint) {
  const RigGeometry rig = Parse(kRig);
  Eigen::Vector2d px;
  ASSERT_TRUE(ProjectToPixel(rig.intrinsics, rig.CameraAt({}), Vec3::Zero(), &px));
  EXPECT_NEAR(px.x(), 400, 1e-9);
  EXPECT_NEAR(px.y(), 300, 1e-9);
  // World +y (away from the camera, which stands at -y) appears up in the image (smaller v).
  ASSERT_TRUE(ProjectToPixel(rig.intrinsics, rig.CameraAt({}), Vec3(0, 0.05, 0), &px));
  EXPECT_LT(px.y(), 300);
  // World +x appears to the right.
  ASSERT_TRUE(ProjectToPixel(rig.intrinsics, rig.CameraAt({}), Vec3(0.05, 0, 0), &px));
  EXPECT_GT(px.x(), 400);
}

TEST(RigGeometryTest, PixelRayInvertsProjectionWithDistortion) {
  const RigGeometry rig = Parse(kRig);
  const CameraPose pose = rig.CameraAt({{"camera_arm", 0.2}});
  const Vec3 point(0.03, -0.02, 0);
  Eigen::Vector2d px;
  ASSERT_TRUE(ProjectToPixel(rig.intrinsics, pose, point, &px));
  const Vec3 ray = PixelRayInWorld(rig.intrinsics, pose, px);
  const Vec3 expected = (point - pose.CenterInWorld()).normalized();
  EXPECT_LT((ray - expected).norm(), 1e-9);
}

TEST(RigGeometryTest, ArmRotationKeepsDistanceToPivot) {
  const RigGeometry rig = Parse(kRig);
  const Vec3 light = rig.LightAt({{"light_arm", 0.5}});
  EXPECT_NEAR(light.norm(), rig.light_position.norm(), 1e-12);
  EXPECT_GT((light - rig.light_position).norm(), 0.1);
  EXPECT_NEAR((rig.CameraAt({{"light_arm", 0.5}}).CenterInWorld() - rig.camera_position).norm(), 0,
              1e-12);
}

TEST(RigGeometryTest, SampleTiltEqualsInverseMotionOfCameraAndLight) {
  const RigGeometry rig = Parse(kRig);
  const Vec3 tilted_light = rig.LightAt({{"tilt", 0.3}});
  const Vec3 arm_light = rig.LightAt({{"light_arm", -0.3}});
  EXPECT_LT((tilted_light - arm_light).norm(), 1e-12);
  const Vec3 tilted_cam = rig.CameraAt({{"tilt", 0.3}}).CenterInWorld();
  const Vec3 arm_cam = rig.CameraAt({{"camera_arm", -0.3}}).CenterInWorld();
  EXPECT_LT((tilted_cam - arm_cam).norm(), 1e-12);
}

TEST(RigGeometryTest, OutOfRangeOrUnknownAxisIsAnError) {
  const RigGeometry rig = Parse(kRig);
  EXPECT_THROW(rig.CameraAt({{"camera_arm", 1.2}}), Error);
  EXPECT_THROW(rig.LightAt({{"elbow", 0.0}}), Error);
}

TEST(RigGeometryTest, BadValuesPointAtFileAndLine) {
  std::string text = kRig;
  text.replace(text.find("moves: light"), 12, "moves: lamp ");
  const std::string error = ParseError(text);
  EXPECT_THAT(error, ::testing::HasSubstr("rig.yaml:14:"));
  EXPECT_THAT(error, ::testing::HasSubstr("expected one of camera, light, sample"));
  std::string typo = kRig;
  typo.replace(typo.find("intensity"), 9, "intensty ");
  EXPECT_THROW(Parse(typo), FileError);
}

}  // namespace
}  // namespace brdfrig::geometry
