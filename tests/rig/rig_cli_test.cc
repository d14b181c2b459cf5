// The `brdfrig rig` commands as a person runs them: the real executable, a simulated drive
// started with `brdfrig rig simdrive`, exit statuses and the lines printed. Guards the
// registration in main.cc (backends and commands) as much as the commands themselves.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
