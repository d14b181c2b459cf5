// A lab on loopback made of processes, as a person sets it up: two `brdfrig rig simdrive`, one
// `brdfrig rig simcamera --rig rig.yaml` photographing the scene at the pose those drives report,
// and the ordinary `brdfrig rig check/move/shoot` on a rig.yaml that names only hardware
// backends (gphoto2 with a ptpip: port, modbus over TCP).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/common/run_brdfrig.h"
#include "tests/sim/test_scene.h"

namespace {

using Result = brdfrig::testing::CommandResult;

Result Brdfrig(const std::string& arguments) { return brdfrig::testing::RunBrdfrig(arguments); }

using Background = brdfrig::testing::BackgroundBrdfrig;

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class SimCameraCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("brdfrig_simcamera_cli_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    setenv("HOME", dir_.c_str(), 1);  // libgphoto2's settings file, for the child processes
    // In sanitizer builds the brdfrig children that open a libgphoto2 camera would end with
    // LeakSanitizer's report of libgphoto2's camlib handles (kept until exit, not ours; see
    // tests/rig/gphoto2_camera_test.cc): leak checking is off for them only.
    const char* asan = getenv("ASAN_OPTIONS");
    setenv("ASAN_OPTIONS", ((asan ? std::string(asan) + ":" : "") + "detect_leaks=0").c_str(), 1);
    std::ofstream(dir_ / "scene.yaml") << brdfrig::sim::testing::BaseSceneYaml();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string WriteRig(const std::string& camera_port, int camera_arm, int light_arm) {
    const auto drive = [](int port) {
      return "{backend: modbus, transport: tcp, host: 127.0.0.1, port: " + std::to_string(port) +
             ", profile: oriental_az_direct, speed_deg_s: 200, accel_deg_s2: 4000}\n";
    };
    std::ofstream(dir_ / "rig.yaml")
        << "geometry: scene.yaml\n"
        << "camera: {backend: gphoto2, port: \"" << camera_port
        << "\", delete_after_download: true, event_drain_s: 0.5}\n"
        << "axes:\n"
        << "  camera_arm: " << drive(camera_arm) << "  light_arm: " << drive(light_arm);
    return (dir_ / "rig.yaml").string();
  }

  std::filesystem::path dir_;
};

TEST_F(SimCameraCliTest, RigCommandsShootRawJpegFromTheSimulatedCameraAtThePoseOfTheDrives) {
  Background camera_arm({"rig", "simdrive", "--tcp", "0"});
  Background light_arm({"rig", "simdrive", "--tcp", "0"});
  ASSERT_GT(camera_arm.port(), 0);
  ASSERT_GT(light_arm.port(), 0);
  // The camera opens the rig file's axes at start (they connect at the first shot); its own
  // port is known once it listens, and goes into the same file.
  const std::string rig = WriteRig("ptpip:0.0.0.0:1", camera_arm.port(), light_arm.port());
  Background camera({"rig", "simcamera", "--listen", "127.0.0.1:0", "--scene",
                     (dir_ / "scene.yaml").string(), "--rig", rig, "--threads", "2"});
  const auto at = camera.first_line().find("ptpip:");
  ASSERT_NE(at, std::string::npos) << camera.first_line();
  const std::string port_path =
      camera.first_line().substr(at, camera.first_line().find(' ', at) - at);
  WriteRig(port_path, camera_arm.port(), light_arm.port());

  const Result check = Brdfrig("rig check --rig " + rig);
  EXPECT_EQ(check.status, 0) << check.output;
  EXPECT_NE(check.output.find("3 of 3 devices OK"), std::string::npos) << check.output;

  std::vector<std::string> dngs;
  for (const char* pose : {"20", "35"}) {
    EXPECT_EQ(Brdfrig("rig move --rig " + rig + " camera_arm " + pose).status, 0);
    EXPECT_EQ(Brdfrig("rig move --rig " + rig + " light_arm -" + std::string(pose)).status, 0);
    const std::string photo = (dir_ / ("shot_" + std::string(pose) + ".jpg")).string();
    const Result shoot = Brdfrig("rig shoot --rig " + rig + " --exposure 1/60 -o " + photo);
    EXPECT_EQ(shoot.status, 0) << shoot.output;
    // The scene's body offers 1/1000, 1/100 and 1/10 s: 1/100 is the nearest in stops.
    EXPECT_NE(shoot.output.find("exposure 1/100 s"), std::string::npos) << shoot.output;
    EXPECT_GT(std::filesystem::file_size(photo), 1000u);
    const auto dng = std::filesystem::path(photo).replace_extension(".DNG");
    ASSERT_TRUE(std::filesystem::exists(dng)) << shoot.output;
    dngs.push_back(ReadAll(dng));
  }
  EXPECT_NE(dngs[0], dngs[1]) << "moving the drives did not change the photo";

  const Result stopped = camera.Stop();
  EXPECT_EQ(stopped.status, 0) << stopped.output;
  EXPECT_NE(stopped.output.find("2 captures"), std::string::npos) << stopped.output;
  EXPECT_NE(stopped.output.find("0 files on the card"), std::string::npos) << stopped.output;
}

TEST_F(SimCameraCliTest, BadListenAddressIsAClearOptionsError) {
  const Result bad =
      Brdfrig("rig simcamera --listen localhost --scene " + (dir_ / "scene.yaml").string());
  EXPECT_EQ(bad.status, 1) << bad.output;
  EXPECT_NE(bad.output.find("--listen must be HOST:PORT"), std::string::npos) << bad.output;
}

}  // namespace
