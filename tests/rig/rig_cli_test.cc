// The `brdfrig rig` commands as a person runs them: the real executable, a simulated drive
// started with `brdfrig rig simdrive`, exit statuses and the lines printed. Guards the
// registration in main.cc (backends and commands) as much as the commands themselves.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "tests/common/run_brdfrig.h"
#include "tests/sim/test_scene.h"

namespace {

using Result = brdfrig::testing::CommandResult;

Result Brdfrig(const std::string& arguments) { return brdfrig::testing::RunBrdfrig(arguments); }

// `brdfrig rig simdrive --tcp 0` in the background; its first line names the port.
class SimDrive : public brdfrig::testing::BackgroundBrdfrig {
 public:
  explicit SimDrive(std::vector<std::string> extra = {})
      : BackgroundBrdfrig(Arguments(std::move(extra))) {}

 private:
  static std::vector<std::string> Arguments(std::vector<std::string> extra) {
    std::vector<std::string> args = {"rig", "simdrive", "--tcp", "0"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
};

class RigCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("brdfrig_rig_cli_test_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "scene.yaml") << brdfrig::sim::testing::BaseSceneYaml();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string WriteRig(int light_arm_port) {
    std::ofstream(dir_ / "rig.yaml")
        << "geometry: scene.yaml\n"
           "camera: {backend: sim, scene: scene.yaml}\n"
           "axes:\n"
           "  light_arm: {backend: modbus, transport: tcp, host: 127.0.0.1, port: "
        << light_arm_port
        << ", profile: oriental_az_direct, speed_deg_s: 200, accel_deg_s2: 4000, "
           "timeout_ms: 200, attempts: 2}\n"
           "  camera_arm: {backend: sim, scene: scene.yaml}\n";
    return (dir_ / "rig.yaml").string();
  }

  std::filesystem::path dir_;
};

TEST_F(RigCliTest, CheckMoveAndShootAgainstASimDriveThenCtrlCStopsIt) {
  SimDrive drive;
  ASSERT_GT(drive.port(), 0);
  const std::string rig = WriteRig(drive.port());

  const Result check = Brdfrig("rig check --rig " + rig);
  EXPECT_EQ(check.status, 0) << check.output;
  EXPECT_NE(check.output.find("3 of 3 devices OK"), std::string::npos) << check.output;

  const Result move = Brdfrig("rig move --rig " + rig + " light_arm -7.5");
  EXPECT_EQ(move.status, 0) << move.output;
  EXPECT_NE(move.output.find("light_arm at -7.500 deg"), std::string::npos) << move.output;

  const std::string photo = (dir_ / "shot.png").string();
  const Result shoot = Brdfrig("rig shoot --rig " + rig + " --exposure 1/60 -o " + photo);
  EXPECT_EQ(shoot.status, 0) << shoot.output;
  EXPECT_TRUE(std::filesystem::exists(photo));

  const Result stopped = drive.Stop();
  EXPECT_EQ(stopped.status, 0) << stopped.output;
  EXPECT_NE(stopped.output.find("final position -750 steps"), std::string::npos) << stopped.output;
}

// `rig calibrate status`: 3 while any value is nominal, with the table saying which.
TEST_F(RigCliTest, CalibrateStatusExitsThreeWhileTheRigRunsOnNominalValues) {
  const Result status = Brdfrig("rig calibrate status --rig " + WriteRig(1));
  EXPECT_EQ(status.status, 3) << status.output;
  EXPECT_NE(status.output.find("lens             NOMINAL"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("recalibrate"), std::string::npos) << status.output;
}

// `rig calibrate light` on a simulated capture of the mirror tile (at 640 x 480 to keep it
// short): the file it writes holds the scene's true light, not the rig file's nominal one; a
// directory that is no capture is an error naming it.
TEST_F(RigCliTest, CalibrateLightWritesTheTrueLightFromAMirrorTileCapture) {
  std::ifstream in(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/mirror_tile.yaml");
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string full = "resolution: [1600, 1200]";
  ASSERT_NE(yaml.find(full), std::string::npos);
  yaml.replace(yaml.find(full), full.size(), "resolution: [640, 480]");
  std::ofstream(dir_ / "mirror.yaml") << yaml;
  const std::string capture = (dir_ / "capture").string();
  ASSERT_EQ(Brdfrig("simulate " + (dir_ / "mirror.yaml").string() + " -o " + capture).status, 0);
  const std::string light = (dir_ / "light.json").string();
  const Result calibrated = Brdfrig("rig calibrate light " + capture + " --scene " +
                                    (dir_ / "mirror.yaml").string() + " -o " + light);
  ASSERT_EQ(calibrated.status, 0) << calibrated.output;
  EXPECT_NE(calibrated.output.find("from 5 photos"), std::string::npos) << calibrated.output;
  std::ifstream file(light);
  const std::string json((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"brdfrig-light-calibration\""), std::string::npos) << json;
  // The scene's true light is [0.003, 0.004, 0.6] (metres); its rig file would say [0, 0, 0.6].
  const std::size_t at = json.find("\"light_position\"");
  ASSERT_NE(at, std::string::npos) << json;
  double x = 0, y = 0, z = 0;
  ASSERT_EQ(std::sscanf(json.c_str() + json.find('[', at), "[ %lf , %lf , %lf", &x, &y, &z), 3)
      << json;
  EXPECT_LT(std::hypot(x - 0.003, y - 0.004, z - 0.6), 0.001) << json;

  const Result refused = Brdfrig("rig calibrate light " + dir_.string() + " -o " + light);
  EXPECT_NE(refused.status, 0);
  EXPECT_NE(refused.output.find(dir_.string()), std::string::npos) << refused.output;
}

TEST_F(RigCliTest, CheckExitsNonZeroWithTheReasonWhenADriveIsMissing) {
  int free_port = 0;
  {
    SimDrive drive;  // take a port that then has nobody listening on it
    free_port = drive.port();
  }
  const Result check = Brdfrig("rig check --rig " + WriteRig(free_port));
  EXPECT_EQ(check.status, 1) << check.output;
  EXPECT_NE(check.output.find("light_arm   FAIL"), std::string::npos) << check.output;
  EXPECT_NE(check.output.find("cannot connect"), std::string::npos) << check.output;
  EXPECT_NE(check.output.find("brdfrig: error: rig check failed"), std::string::npos)
      << check.output;
}

TEST_F(RigCliTest, AnAlarmRehearsedWithSimdriveEndsTheMoveWithItsCodeAndAStop) {
  SimDrive drive({"--alarm-at", "0.5", "--alarm-code", "66"});
  ASSERT_GT(drive.port(), 0);
  const Result move = Brdfrig("rig move --rig " + WriteRig(drive.port()) + " light_arm 20");
  EXPECT_EQ(move.status, 1) << move.output;
  EXPECT_NE(move.output.find("drive alarm 0x42"), std::string::npos) << move.output;
  EXPECT_NE(move.output.find("the drive was stopped"), std::string::npos) << move.output;
  const Result stopped = drive.Stop();
  EXPECT_EQ(stopped.output.find(", 0 stops"), std::string::npos) << stopped.output;
}

TEST_F(RigCliTest, SimdriveNeedsExactlyOneTransport) {
  const Result both = Brdfrig("rig simdrive --tcp 0 --pty");
  EXPECT_EQ(both.status, 1) << both.output;
  EXPECT_NE(both.output.find("exactly one of --tcp PORT and --pty"), std::string::npos)
      << both.output;
}

}  // namespace
