// Needs a real tethered camera (label `hardware`, excluded from CI): run in the lab with
//   ctest --preset release -L hardware
// Optional environment: BRDFRIG_CAMERA_MODEL, BRDFRIG_CAMERA_PORT (default: first found),
// BRDFRIG_CAMERA_CAPTURE_TARGET (card or ram).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "rig/gphoto2_camera.h"

// libgphoto2's state kept until exit: see gphoto2_camera_test.cc.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libgphoto2.so\nleak:libgphoto2_port.so\nleak:libltdl.so\n";
}
extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }

namespace brdfrig::rig {
namespace {

Gphoto2Options FromEnvironment() {
  Gphoto2Options options;
  if (const char* model = std::getenv("BRDFRIG_CAMERA_MODEL")) options.model = model;
  if (const char* port = std::getenv("BRDFRIG_CAMERA_PORT")) options.port = port;
  // Not every body has capturetarget (many Sony models do not): only when asked for.
  if (const char* target = std::getenv("BRDFRIG_CAMERA_CAPTURE_TARGET")) {
    options.capture_target = target;
  }
  return options;
}

TEST(Gphoto2HardwareTest, OpensSetsTheNearestShutterSpeedAndCaptures) {
  Gphoto2Camera camera(FromEnvironment());
  const CameraInfo info = camera.Info();
  std::printf("camera: %s at %s, serial %s, firmware %s, %zu shutter speeds\n", info.model.c_str(),
              info.port.c_str(), info.serial.c_str(), info.firmware.c_str(),
              info.shutter_speeds.size());
  ASSERT_FALSE(info.shutter_speeds.empty()) << "set the mode dial to M";
  const double used = camera.SetExposure(1.0 / 60);
  EXPECT_NEAR(std::log2(used * 60), 0, 0.5);
  const std::vector<Frame> frames = camera.Capture();
  ASSERT_FALSE(frames.empty());
  for (const Frame& f : frames) {
    EXPECT_GT(f.bytes.size(), 1000u) << f.file_name;
    EXPECT_DOUBLE_EQ(f.exposure_s, used);
  }
}

TEST(Gphoto2HardwareTest, ReopenFindsTheSameCameraAgain) {
  Gphoto2Camera camera(FromEnvironment());
  const std::string model = camera.Info().model;
  camera.Reopen();
  EXPECT_EQ(camera.Info().model, model);
}

}  // namespace
}  // namespace brdfrig::rig
