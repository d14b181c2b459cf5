// `brdfrig rig simcamera` under bad clients, through the real binary as the issue saw it
// (issue 25, finding 9): Ctrl-C stops the camera while a client has stopped reading, and under
// a 64-descriptor limit hundreds of GUID-less and idle clients neither exhaust its descriptors
// nor spin it, and a real initiator is served.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/time.h>

#include <filesystem>
#include <fstream>

#include "tests/sim/test_scene.h"
#include "tests/simcamera/camera_process.h"
#include "tests/simcamera/ptpip_test_client.h"

namespace brdfrig::simcamera {
namespace {

using namespace std::chrono_literals;
using testing::CameraProcess;

class SimCameraBadClientsCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("brdfrig_simcamera_bad_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "scene.yaml") << sim::testing::BaseSceneYaml();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::vector<std::string> Args() const {
    return {"rig", "simcamera", "--listen", "127.0.0.1:0", "--scene", (dir_ / "scene.yaml")};
  }

  std::filesystem::path dir_;
};

TEST_F(SimCameraBadClientsCliTest, CtrlCStopsTheCameraWhileAClientHasStoppedReading) {
  CameraProcess camera(Args());
  ASSERT_GT(camera.port(), 0) << camera.first_lines();
  const int client = testing::ConnectTo(camera.port(), 4096);
  ASSERT_NE(testing::InitCommand(client), 0u);
  // Requests that are answered with the device's description, sent and never read: the
  // camera's send buffer fills (before the fix its thread then blocked in send() for ever).
  PtpWriter request;
  request.U32(1).U16(op::kGetDeviceInfo).U32(1);
  const std::vector<std::uint8_t> packet =
      EncodePacket(PacketType::kOperationRequest, request.bytes());
  auto last_progress = std::chrono::steady_clock::now();
  for (int sent = 0; sent < 200000 && std::chrono::steady_clock::now() - last_progress < 500ms;) {
    if (send(client, packet.data(), packet.size(), MSG_NOSIGNAL | MSG_DONTWAIT) > 0) {
      ++sent;
      last_progress = std::chrono::steady_clock::now();
    } else {
      std::this_thread::sleep_for(5ms);
    }
  }
  const CameraProcess::Stopped stopped = camera.Stop(3s);
  close(client);
  ASSERT_TRUE(stopped.exited) << "Ctrl-C did not stop the camera within 3 s";
  EXPECT_EQ(stopped.status, 0) << stopped.output;
  EXPECT_NE(stopped.output.find("stopped:"), std::string::npos) << stopped.output;
}

TEST_F(SimCameraBadClientsCliTest, UnderA64DescriptorLimitBadClientsNeitherLockOutNorSpin) {
  CameraProcess camera(Args(), 64);
  ASSERT_GT(camera.port(), 0) << camera.first_lines();
  const timeval second{1, 0};
  for (int i = 0; i < 200; ++i) {
    const int fd = testing::ConnectTo(camera.port());
    ASSERT_GE(fd, 0) << "connection " << i << " refused";
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &second, sizeof second);
    WritePacket(fd, PacketType::kInitCommandRequest, {0, 0, 0, 0});  // no GUID
    // Before the fix the camera kept every such descriptor (208 open after 200).
    ASSERT_TRUE(testing::ClosedByServer(fd)) << "GUID-less newcomer " << i << " was kept open";
    close(fd);
  }
  std::vector<int> idle;
  for (int i = 0; i < 100; ++i) idle.push_back(testing::ConnectTo(camera.port()));
  std::this_thread::sleep_for(200ms);
  EXPECT_LT(camera.open_descriptors(), 40);
  // With the idle connections held the camera sleeps (before the fix, out of descriptors,
  // it spun at 70 % CPU refusing everyone)...
  const double cpu = camera.cpu_seconds();
  std::this_thread::sleep_for(1s);
  EXPECT_LT(camera.cpu_seconds() - cpu, 0.3);
  // ...and serves an initiator at once.
  const auto start = std::chrono::steady_clock::now();
  {
    testing::Initiator initiator(camera.port());
    EXPECT_EQ(testing::Operation(initiator.command, op::kOpenSession, 0, {1}), rc::kOk);
    EXPECT_EQ(testing::Operation(initiator.command, op::kGetStorageIds, 1), rc::kOk);
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  for (int fd : idle) close(fd);
  const CameraProcess::Stopped stopped = camera.Stop(3s);
  ASSERT_TRUE(stopped.exited);
  EXPECT_EQ(stopped.status, 0) << stopped.output;
}

}  // namespace
}  // namespace brdfrig::simcamera
