// The light calibration finds the simulator's true light (5 mm from the rig file's nominal) within
// 1 mm from a black-glass mirror tile at five positions (sim/scenes/mirror_tile.yaml), and
// refuses what cannot locate it: a matte tile, mirror points all at the cut-out's centre, photos
// given the wrong positions, photos of another camera.
#include "calibrate/light_calibration.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "sim/devices.h"
#include "sim/scene.h"
#include "sim/world.h"

namespace brdfrig::calibrate {
namespace {

const geometry::Vec3 kNominalLight(0, 0, 0.6);  // what the rig file says

std::string MirrorSceneYaml() {
  return ReadFileToString(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/mirror_tile.yaml");
}

// The same scene at 640 x 480: the refusals do not depend on the pixel count.
std::string SmallMirrorSceneYaml() {
  std::string yaml = MirrorSceneYaml();
  const std::string full = "resolution: [1600, 1200]";
  yaml.replace(yaml.find(full), full.size(), "resolution: [640, 480]");
  return yaml;
}

// One photo at each of the scene's capture positions (its shortest exposure).
std::vector<LightPhoto> Photos(const sim::Scene& scene) {
  auto world = std::make_shared<sim::SimWorld>(scene);
  sim::SimCamera camera(world, {}, 0);
  std::vector<LightPhoto> photos;
  for (const geometry::AxisPositions& positions : scene.capture.positions) {
    for (const geometry::RotationAxis& axis : scene.rig.axes) {  // an axis not named: at 0
      world->MoveAxis(axis.name, positions.count(axis.name) ? positions.at(axis.name) : 0.0);
    }
    camera.SetExposure(scene.capture.exposures.front());
    const std::vector<rig::Frame> frames = camera.Capture();
    const std::vector<std::byte>& bytes = frames.front().bytes;
    const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8U,
                          const_cast<std::byte*>(bytes.data()));
    photos.push_back({{"position_" + std::to_string(photos.size()) + ".png",
                       cv::imdecode(encoded, cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH)},
                      positions});
  }
  return photos;
}

// The lab's belief: the scene's rig with the rig file's nominal light.
geometry::RigGeometry Believed(const sim::Scene& scene) {
  geometry::RigGeometry rig = scene.rig;
  rig.light_position = kNominalLight;
  return rig;
}

std::string RefusalOf(const std::vector<LightPhoto>& photos, const geometry::RigGeometry& rig) {
  try {
    CalibrateLight(photos, rig, {});
  } catch (const Error& e) {
    return e.what();
  }
  return "(not refused)";
}

class LightCalibrationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new sim::Scene(sim::LoadSceneString(MirrorSceneYaml(), "mirror_tile.yaml"));
    photos_ = new std::vector<LightPhoto>(Photos(*scene_));
  }
  static void TearDownTestSuite() {
    delete photos_;
    delete scene_;
  }
  static sim::Scene* scene_;
  static std::vector<LightPhoto>* photos_;
};
sim::Scene* LightCalibrationTest::scene_ = nullptr;
std::vector<LightPhoto>* LightCalibrationTest::photos_ = nullptr;

TEST_F(LightCalibrationTest, TrueLightIsFoundWithinOneMillimetre) {
  const LightCalibrationResult result = CalibrateLight(*photos_, Believed(*scene_), {});
  const geometry::Vec3 truth = scene_->rig.light_position;
  const double error = (result.light_position - truth).norm();
  std::printf("%serror %.3f mm (the nominal light is %.3f mm off)\n", result.ToString().c_str(),
              1e3 * error, 1e3 * (kNominalLight - truth).norm());
  EXPECT_LT(error, 0.001);
  EXPECT_NEAR(result.nominal_offset_m, (truth - kNominalLight).norm(), 0.001);
  EXPECT_LT(result.rms_miss_m, 0.0005);
  ASSERT_EQ(result.photos.size(), photos_->size());
}

TEST_F(LightCalibrationTest, PhotosGivenTheWrongPositionsAreRefused) {
  std::vector<LightPhoto> swapped = *photos_;
  std::swap(swapped[0].positions, swapped[2].positions);
  EXPECT_NE(RefusalOf(swapped, Believed(*scene_)).find("misses the light"), std::string::npos)
      << RefusalOf(swapped, Believed(*scene_));
}

TEST_F(LightCalibrationTest, PhotosOfAnotherCameraAreRefused) {
  std::vector<LightPhoto> small = *photos_;
  cv::resize(small[1].photo.image, small[1].photo.image, cv::Size(800, 600));
  EXPECT_NE(RefusalOf(small, Believed(*scene_)).find("another camera"), std::string::npos);
}

TEST_F(LightCalibrationTest, TooFewPhotosAreRefused) {
  const std::vector<LightPhoto> two(photos_->begin(), photos_->begin() + 2);
  EXPECT_NE(RefusalOf(two, Believed(*scene_)).find("at least 3"), std::string::npos);
}

TEST(LightCalibrationRefusalTest, MatteTileHasNoMirrorHighlight) {
  std::string yaml = SmallMirrorSceneYaml();
  const std::string glass = "{model: ggx, alpha: 0.01, f0: 0.04, diffuse: 0}";
  ASSERT_NE(yaml.find(glass), std::string::npos);
  yaml.replace(yaml.find(glass), glass.size(), "{model: lambert, albedo: 0.5}");
  const std::string exposure = "exposures: [0.00025]";
  yaml.replace(yaml.find(exposure), exposure.size(), "exposures: [0.0333333]");
  const sim::Scene scene = sim::LoadSceneString(yaml, "matte.yaml");
  const std::string refusal = RefusalOf(Photos(scene), Believed(scene));
  EXPECT_NE(refusal.find("no mirror highlight"), std::string::npos) << refusal;
}

TEST(LightCalibrationRefusalTest, MirrorPointsAllAtTheCentreCannotTellTheDistance) {
  // Symmetric arms put every mirror point at the cut-out's centre: in the light's own frame the
  // rays coincide, whatever the arms' angles.
  std::string yaml = SmallMirrorSceneYaml();
  const std::size_t from = yaml.find("  positions:");
  const std::size_t to = yaml.find("\neffects:");
  yaml.replace(from, to - from,
               "  positions: [{camera_arm: 20, light_arm: -20}, {camera_arm: 35, light_arm: -35},"
               " {camera_arm: 50, light_arm: -50}]\n");
  const sim::Scene scene = sim::LoadSceneString(yaml, "centred.yaml");
  const std::string refusal = RefusalOf(Photos(scene), Believed(scene));
  EXPECT_NE(refusal.find("cannot tell where along them"), std::string::npos) << refusal;
}

}  // namespace
}  // namespace brdfrig::calibrate
