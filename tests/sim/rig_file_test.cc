// rig.yaml assembled through the backend registry, with the simulator as the backend.
#include "rig/rig_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "sim/devices.h"
#include "tests/sim/test_scene.h"

namespace brdfrig::sim {
namespace {

using testing::BaseSceneYaml;

class RigFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / "brdfrig_rig_file_test";
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "scene.yaml") << BaseSceneYaml();
    RegisterSimBackends();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path WriteRig(const std::string& text) {
    std::ofstream(dir_ / "rig.yaml") << text;
    return dir_ / "rig.yaml";
  }

  std::filesystem::path dir_;
};

TEST_F(RigFileTest, OpensEveryDeviceAndReadsGeometryFromTheSceneFile) {
  const auto file = WriteRig(R"(geometry: scene.yaml
camera: {backend: sim, scene: scene.yaml}
axes:
  camera_arm: {backend: sim, scene: scene.yaml}
  light_arm: {backend: sim, scene: scene.yaml}
light: {backend: sim, scene: scene.yaml}
)");
  rig::Rig rig = rig::OpenRig(file);
  ASSERT_TRUE(rig.camera);
  ASSERT_TRUE(rig.light);
  ASSERT_EQ(rig.axes.size(), 2u);
  EXPECT_EQ(rig.axes.at("light_arm")->Name(), "light_arm");
  EXPECT_NE(rig.description.geometry.FindAxis("camera_arm"), nullptr);
  EXPECT_EQ(rig.description.source_files.size(), 2u);
  const rig::MoveReport report = rig.axes.at("camera_arm")->MoveTo(0.2);
  EXPECT_NEAR(report.position, 0.2, 1e-3);
}

TEST_F(RigFileTest, AxisMissingFromTheGeometryIsAnErrorAtItsLine) {
  const auto file = WriteRig(R"(geometry: scene.yaml
camera: {backend: sim, scene: scene.yaml}
axes:
  tilt: {backend: sim, scene: scene.yaml}
)");
  try {
    rig::ReadRigDescription(file);
    FAIL() << "unknown axis accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.yaml:4:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("tilt"), std::string::npos) << e.what();
  }
}

TEST_F(RigFileTest, MissingBackendUnknownKeyAndMissingGeometryFileAreErrors) {
  EXPECT_THROW(rig::ReadRigDescription(WriteRig("geometry: scene.yaml\ncamera: {scene: x}\n")),
               FileError);
  EXPECT_THROW(rig::ReadRigDescription(
                   WriteRig("geometry: scene.yaml\ncamera: {backend: sim}\ncamer: {}\n")),
               FileError);
  EXPECT_THROW(
      rig::ReadRigDescription(WriteRig("geometry: nowhere.yaml\ncamera: {backend: sim}\n")),
      FileError);
  EXPECT_THROW(
      rig::OpenRig(WriteRig("geometry: scene.yaml\ncamera: {backend: gphoto3, scene: s}\n")),
      FileError);
}

}  // namespace
}  // namespace brdfrig::sim
