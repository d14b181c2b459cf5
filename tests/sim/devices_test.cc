// Simulated devices behave like the rig interfaces promise: the camera sees where the sim axes
// put the arms, time is virtual (or real on request), and scheduled faults throw the rig error
// types at the scheduled moment.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "rig/backend_registry.h"
#include "sim/devices.h"
#include "test_scene.h"

namespace brdfrig::sim {
namespace {

using rig::AxisError;
using rig::CameraError;
using testing::BaseSceneYaml;
using testing::TestScene;

constexpr double kDegree = M_PI / 180.0;

std::shared_ptr<SimWorld> World(const std::string& extra = "") {
  return std::make_shared<SimWorld>(TestScene(extra));
}

cv::Mat Decode(const rig::Frame& frame) {
  return cv::imdecode(cv::Mat(1, static_cast<int>(frame.bytes.size()), CV_8U,
                              const_cast<std::byte*>(frame.bytes.data())),
                      cv::IMREAD_UNCHANGED);
}

TEST(DevicesTest, CameraPhotographsWhereTheAxesPutTheArms) {
  auto world = World();
  SimCamera camera(world);
  SimAxis camera_arm(world, "camera_arm"), light_arm(world, "light_arm");
  camera_arm.MoveTo(25 * kDegree);
  light_arm.MoveTo(-15 * kDegree);
  EXPECT_DOUBLE_EQ(camera.SetExposure(0.012), 0.01);  // nearest offered shutter speed
  const std::vector<rig::Frame> frames = camera.Capture();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].file_name, "SIM_0001.png");
  const geometry::AxisPositions positions = {{"camera_arm", 25 * kDegree},
                                             {"light_arm", -15 * kDegree}};
  const Simulator& simulator = world->simulator();
  const std::vector<std::byte> expected =
      simulator.EncodePhoto(simulator.RenderCameraImage(positions, 0.01, 1));
  EXPECT_EQ(frames[0].bytes, expected);
  EXPECT_EQ(Decode(frames[0]).type(), CV_16UC3);
  // Elsewhere, the photo differs.
  camera_arm.MoveTo(35 * kDegree);
  EXPECT_NE(camera.Capture()[0].bytes, expected);
}

TEST(DevicesTest, MovesAndShotsTakeVirtualTime) {
  auto world = World();
  SimAxis arm(world, "camera_arm");
  // 30° at 20°/s with 40°/s²: 0.5 s accelerating, 1.0 s cruising, 0.5 s braking.
  const rig::MoveReport move = arm.MoveTo(30 * kDegree);
  EXPECT_NEAR(move.duration_s, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(move.position, 30 * kDegree);
  // 5°: too short for full speed, a triangle profile: 2·sqrt(5/40).
  EXPECT_NEAR(arm.MoveTo(35 * kDegree).duration_s, 2 * std::sqrt(5.0 / 40.0), 1e-12);
  SimCamera camera(world);
  camera.SetExposure(0.1);
  const rig::Frame frame = camera.Capture()[0];
  EXPECT_NEAR(frame.exposure_duration_s, 0.1 + 0.25, 1e-12);
  EXPECT_NEAR(frame.download_duration_s, 1.5, 1e-12);
  EXPECT_NEAR(world->virtual_time_s(), 2.0 + 2 * std::sqrt(5.0 / 40.0) + 0.35 + 1.5, 1e-9);
}

TEST(DevicesTest, RealTimeModeSleepsTheScaledDuration) {
  auto world = World();
  auto scene = world->scene();
  scene.timing.real_time_factor = 0.05;  // 2 s move → 100 ms
  SimWorld real(scene);
  const auto start = std::chrono::steady_clock::now();
  real.MoveAxis("camera_arm", 30 * kDegree);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(wall, 0.095);
  EXPECT_LT(wall, 1.0);
}

TEST(DevicesTest, AxisRefusesTargetsOutsideItsRange) {
  auto world = World();
  SimAxis arm(world, "light_arm");
  try {
    arm.MoveTo(85 * kDegree);
    FAIL() << "no error";
  } catch (const AxisError& e) {
    EXPECT_EQ(e.kind(), AxisError::Kind::kLimits);
  }
  EXPECT_EQ(arm.Status().state, rig::AxisState::kReady);
  EXPECT_DOUBLE_EQ(arm.Status().position, 0);
}

TEST(DevicesTest, ScheduledAxisAlarmStopsTheAxisUntilReset) {
  auto world =
      World("faults:\n  - {type: axis_alarm, axis: light_arm, at_move: 2, alarm_code: 66}\n");
  SimAxis arm(world, "light_arm");
  arm.MoveTo(-10 * kDegree);
  try {
    arm.MoveTo(-20 * kDegree);
    FAIL() << "no alarm";
  } catch (const AxisError& e) {
    EXPECT_EQ(e.kind(), AxisError::Kind::kAlarm);
    EXPECT_EQ(e.alarm_code(), 66);
  }
  EXPECT_EQ(arm.Status().state, rig::AxisState::kAlarm);
  EXPECT_EQ(arm.Status().alarm_code, 66);
  EXPECT_DOUBLE_EQ(arm.Status().position, -10 * kDegree);  // it did not move
  EXPECT_THROW(arm.MoveTo(-20 * kDegree), AxisError);
  arm.ResetAlarm();
  EXPECT_EQ(arm.Status().state, rig::AxisState::kReady);
  EXPECT_DOUBLE_EQ(arm.MoveTo(-20 * kDegree).position, -20 * kDegree);
  arm.Home();
  EXPECT_DOUBLE_EQ(arm.Status().position, 0);
}

TEST(DevicesTest, ScheduledBusyAnswersComeAtTheirShot) {
  auto world = World("faults:\n  - {type: camera_busy, at_shot: 2, count: 2}\n");
  SimCamera camera(world);
  EXPECT_EQ(camera.Capture()[0].file_name, "SIM_0001.png");
  for (int i = 0; i < 2; ++i) {
    try {
      camera.Capture();
      FAIL() << "no busy answer";
    } catch (const CameraError& e) {
      EXPECT_EQ(e.kind(), CameraError::Kind::kBusy);
      EXPECT_TRUE(e.recoverable());
    }
  }
  EXPECT_EQ(camera.Capture()[0].file_name, "SIM_0002.png");
}

TEST(DevicesTest, ScheduledDisconnectNeedsReopenAndComesBackAfterFailures) {
  auto world =
      World("faults:\n  - {type: camera_disconnect, after_shots: 2, reopen_failures: 2}\n");
  SimCamera camera(world);
  camera.Capture();
  camera.Capture();
  try {
    camera.Capture();
    FAIL() << "no disconnect";
  } catch (const CameraError& e) {
    EXPECT_EQ(e.kind(), CameraError::Kind::kGone);
  }
  EXPECT_THROW(camera.SetExposure(0.01), CameraError);
  for (int i = 0; i < 2; ++i) {
    try {
      camera.Reopen();
      FAIL() << "camera back too early";
    } catch (const CameraError& e) {
      EXPECT_EQ(e.kind(), CameraError::Kind::kNotFound);
    }
  }
  camera.Reopen();
  EXPECT_EQ(camera.Capture()[0].file_name, "SIM_0003.png");
  EXPECT_EQ(camera.Capture()[0].file_name, "SIM_0004.png");  // it happens once
}

TEST(DevicesTest, ScheduledSlowDownloadLengthensThoseFrames) {
  auto world = World("faults:\n  - {type: slow_download, at_shot: 2, count: 2, duration_s: 30}\n");
  SimCamera camera(world);
  EXPECT_DOUBLE_EQ(camera.Capture()[0].download_duration_s, 1.5);
  EXPECT_DOUBLE_EQ(camera.Capture()[0].download_duration_s, 30);
  EXPECT_DOUBLE_EQ(camera.Capture()[0].download_duration_s, 30);
  EXPECT_DOUBLE_EQ(camera.Capture()[0].download_duration_s, 1.5);
}

TEST(DevicesTest, LightOffLeavesADarkPhoto) {
  auto world = World();
  SimCamera camera(world);
  SimLight light(world);
  light.SetOn(false);
  const cv::Mat dark = Decode(camera.Capture()[0]);
  EXPECT_EQ(cv::countNonZero(dark.reshape(1)), 0);
  light.SetOn(true);
  EXPECT_GT(cv::countNonZero(Decode(camera.Capture()[0]).reshape(1)), 0);
}

TEST(DevicesTest, CameraWritesTruthApartWhenAsked) {
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_sim_devices_truth";
  std::filesystem::remove_all(dir);
  auto world = World();
  SimCamera camera(world, dir);
  camera.Capture();
  camera.Capture();  // same pose: no second EXR
  EXPECT_TRUE(std::filesystem::exists(dir / "SIM_0001.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "SIM_0002.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "SIM_0001_radiance.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir / "SIM_0002_radiance.exr"));
  std::filesystem::remove_all(dir);
}

TEST(DevicesTest, SimBackendsShareOneWorldPerSceneFile) {
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_sim_backend_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.yaml") << BaseSceneYaml();
  RegisterSimBackends();
  const YamlNode rig_file = LoadYamlString(R"(camera: {scene: scene.yaml}
light_arm: {scene: scene.yaml}
arm: {scene: scene.yaml, axis: camera_arm}
lamp: {scene: scene.yaml}
bad: {scene: scene.yaml, axis: tilt}
typo: {scene: scene.yaml, sceen: 1}
)",
                                           "rig.yaml");
  const rig::DeviceContext context{"camera", dir.string()};
  auto camera = rig::CreateCamera("sim", rig_file.Required("camera"), context);
  auto light_arm =
      rig::CreateAxis("sim", rig_file.Required("light_arm"), {"light_arm", dir.string()});
  auto arm = rig::CreateAxis("sim", rig_file.Required("arm"), {"arm", dir.string()});
  auto lamp = rig::CreateLight("sim", rig_file.Required("lamp"), {"lamp", dir.string()});
  EXPECT_EQ(light_arm->Name(), "light_arm");
  EXPECT_EQ(arm->Name(), "camera_arm");
  arm->MoveTo(20 * kDegree);
  light_arm->MoveTo(-10 * kDegree);
  camera->SetExposure(0.01);
  const rig::Frame frame = camera->Capture()[0];
  const Simulator simulator(LoadScene(dir / "scene.yaml"));
  EXPECT_EQ(frame.bytes,
            simulator.EncodePhoto(simulator.RenderCameraImage(
                {{"camera_arm", 20 * kDegree}, {"light_arm", -10 * kDegree}}, 0.01, 1)));
  lamp->SetOn(false);
  EXPECT_EQ(cv::countNonZero(Decode(camera->Capture()[0]).reshape(1)), 0);
  EXPECT_THROW(rig::CreateAxis("sim", rig_file.Required("bad"), {"bad", dir.string()}), FileError);
  try {
    rig::CreateAxis("sim", rig_file.Required("typo"), {"typo", dir.string()});
    FAIL() << "unknown key accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("rig.yaml:6:"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace brdfrig::sim
