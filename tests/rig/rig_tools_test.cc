// `brdfrig rig check|move|shoot` as library calls, on a rig.yaml with the simulated camera and
// Modbus axes served by simulated drives over loopback TCP (the real Modbus client runs).
#include "rig/rig_tools.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "rig/hardware_backends.h"
#include "sim/devices.h"
#include "sim/modbus_drive_server.h"
#include "tests/sim/test_scene.h"

namespace brdfrig::rig {
namespace {

class RigToolsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::RegisterSimBackends();
    RegisterHardwareBackends();
    dir_ = std::filesystem::temp_directory_path() /
           ("brdfrig_rig_tools_test_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "scene.yaml") << sim::testing::BaseSceneYaml();
    const DriveProfile az = LoadDriveProfile("oriental_az_direct");
    light_drive_ = std::make_unique<sim::ModbusDriveServer>(az, sim::DriveServerOptions{});
    camera_drive_ = std::make_unique<sim::ModbusDriveServer>(az, sim::DriveServerOptions{});
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Axis(const sim::ModbusDriveServer& drive) const {
    return "{backend: modbus, transport: tcp, host: 127.0.0.1, port: " +
           std::to_string(drive.port()) +
           ", slave: 1, profile: oriental_az_direct, steps_per_degree: 100, speed_deg_s: 200, "
           "accel_deg_s2: 4000, min_deg: -80, max_deg: 80, timeout_ms: 100, poll_ms: 5}";
  }

  std::filesystem::path WriteRig(const std::string& extra = "") {
    std::ofstream(dir_ / "rig.yaml")
        << "geometry: scene.yaml\n"
           "camera: {backend: sim, scene: scene.yaml}\n"
           "axes:\n"
           "  light_arm: "
        << Axis(*light_drive_) << "\n  camera_arm: " << Axis(*camera_drive_) << "\n"
        << extra;
    return dir_ / "rig.yaml";
  }

  std::filesystem::path dir_;
  std::unique_ptr<sim::ModbusDriveServer> light_drive_, camera_drive_;
};

TEST_F(RigToolsTest, CheckFindsEveryDeviceAndReportsPositions) {
  const RigCheckReport report = CheckRig(WriteRig());
  EXPECT_TRUE(report.ok()) << report.ToString();
  ASSERT_EQ(report.devices.size(), 3u);
  const std::string text = report.ToString();
  EXPECT_NE(text.find("light_arm"), std::string::npos) << text;
  EXPECT_NE(text.find("profile oriental_az_direct: ready at 0.000 deg"), std::string::npos) << text;
  EXPECT_NE(text.find("(100 steps/deg, limits -80..80 deg, 200 deg/s"), std::string::npos) << text;
  EXPECT_NE(text.find("3 of 3 devices OK"), std::string::npos) << text;
}

TEST_F(RigToolsTest, MoveDrivesTheNamedAxisOnly) {
  const auto file = WriteRig();
  const MoveReport report = MoveAxis(file, "light_arm", 12.5);
  EXPECT_NEAR(report.position * 180 / M_PI, 12.5, 0.02);
  EXPECT_EQ(light_drive_->position_steps(), 1250);
  EXPECT_EQ(camera_drive_->counters().requests, 0);
  const RigCheckReport check = CheckRig(file);
  EXPECT_NE(check.ToString().find("ready at 12.500 deg"), std::string::npos) << check.ToString();
  EXPECT_THROW(MoveAxis(file, "tilt", 1), Error);
  try {
    MoveAxis(file, "light_arm", 95);
    FAIL();
  } catch (const AxisError& e) {
    EXPECT_EQ(e.kind(), AxisError::Kind::kLimits);
  }
}

TEST_F(RigToolsTest, ShootWritesTheFileWithTheNearestExposure) {
  const auto output = dir_ / "shot.png";
  const ShootReport report = Shoot(WriteRig(), "1/60", output);
  ASSERT_EQ(report.files.size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(report.files[0]));
  EXPECT_GT(std::filesystem::file_size(report.files[0]), 100u);
  // The scene's sensor offers 0.001, 0.01 and 0.1 s: 1/60 is nearest to 0.01 s.
  EXPECT_NEAR(report.exposure_s, 0.01, 1e-9);
  EXPECT_THROW(Shoot(WriteRig(), "soon", output), OptionsError);
}

TEST_F(RigToolsTest, CheckReportsAMissingDriveAndAnAlarmWithReasonsAndIsNotOk) {
  const auto file = WriteRig();
  camera_drive_.reset();  // the drive is switched off: nothing listens on its port
  sim::DriveFaults faults;
  faults.alarm_at_fraction = 0.2;
  light_drive_->InjectFaults(faults);
  EXPECT_THROW(MoveAxis(file, "light_arm", 10), AxisError);
  const RigCheckReport report = CheckRig(file);
  EXPECT_FALSE(report.ok());
  const std::string text = report.ToString();
  EXPECT_NE(text.find("camera_arm  FAIL"), std::string::npos) << text;
  EXPECT_NE(text.find("cannot connect"), std::string::npos) << text;
  EXPECT_NE(text.find("ALARM 0x30"), std::string::npos) << text;
  EXPECT_NE(text.find("1 of 3 devices OK"), std::string::npos) << text;
}

TEST_F(RigToolsTest, ConfigurationErrorsNameFileAndLine) {
  const auto file = WriteRig("light: {backend: modbus, transport: tcp, host: 127.0.0.1}\n");
  try {
    CheckRig(file);
    FAIL() << "light without a coil accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.yaml:6:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("coil"), std::string::npos) << e.what();
  }
}

TEST_F(RigToolsTest, CoilLightIsReportedOnOrOff) {
  const auto file = WriteRig("light: {backend: modbus, transport: tcp, host: 127.0.0.1, port: " +
                             std::to_string(light_drive_->port()) + ", coil: 2}\n");
  const RigCheckReport report = CheckRig(file);
  EXPECT_TRUE(report.ok()) << report.ToString();
  EXPECT_NE(report.ToString().find("coil 2: off"), std::string::npos) << report.ToString();
}

}  // namespace
}  // namespace brdfrig::rig
