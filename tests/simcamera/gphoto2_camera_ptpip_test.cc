// The project's libgphoto2 camera class on a `ptpip:` port: the code path a lab runs (open,
// settings, capture, RAW+JPEG event draining, download, delete, reopen) through libgphoto2's
// real ptp2 driver, with the simulated camera on the other end of the sockets — and every
// camera fault the simulator can inject, each ending in its documented outcome (docs/rig.md).
#include <fcntl.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "rig/gphoto2_camera.h"
#include "sim_camera_fixture.h"

// libgphoto2 keeps its camlib handles until exit (see tests/rig/gphoto2_camera_test.cc).
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libgphoto2.so\nleak:libgphoto2_port.so\nleak:libltdl.so\n";
}
extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }

namespace brdfrig::simcamera {
namespace {

using rig::CameraError;
using Kind = rig::CameraError::Kind;

class Gphoto2PtpipTest : public SimCameraTest {
 protected:
  rig::Gphoto2Options Options() const {
    rig::Gphoto2Options options;
    options.port = server_->PortPath();  // the model defaults to libgphoto2's "PTP/IP Camera"
    options.operation_timeout = std::chrono::milliseconds(20000);
    options.event_drain = std::chrono::milliseconds(1000);
    options.delete_after_download = true;
    options.busy_backoff = std::chrono::milliseconds(20);
    return options;
  }

  static bool HasFile(const std::vector<rig::Frame>& frames, const std::string& extension) {
    return std::any_of(frames.begin(), frames.end(), [&](const rig::Frame& f) {
      return f.file_name.size() > 4 && f.file_name.substr(f.file_name.size() - 4) == extension;
    });
  }

  // Expects `call` to throw a CameraError of `kind`; returns its message.
  template <typename Call>
  std::string ExpectError(Call call, Kind kind) {
    try {
      call();
    } catch (const CameraError& e) {
      EXPECT_EQ(static_cast<int>(e.kind()), static_cast<int>(kind)) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "no CameraError";
    return "";
  }
};

TEST_F(Gphoto2PtpipTest, OpensReportsShutterSpeedsAndCapturesARawJpegPairThatIsDeletedAfter) {
  rig::Gphoto2Camera camera(Options());
  EXPECT_EQ(camera.Info().model, "PTP/IP Camera");
  EXPECT_EQ(camera.Info().serial, "SIMPTPIP0001");
  ASSERT_EQ(camera.Info().shutter_speeds.size(), 4u);
  EXPECT_NEAR(camera.SetExposure(1.0 / 60), 0.0167, 1e-9);
  EXPECT_NEAR(server_->exposure().exposure_s, 0.0167, 1e-9);

  const std::vector<rig::Frame> frames = camera.Capture();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].file_name, "IMG_0001.JPG");  // what gp_camera_capture returns
  EXPECT_TRUE(HasFile(frames, ".DNG"));            // announced afterwards, drained
  for (const rig::Frame& f : frames) {
    EXPECT_GT(f.bytes.size(), 1000u) << f.file_name;
    EXPECT_NEAR(f.exposure_s, 0.0167, 1e-9);
    EXPECT_EQ(f.iso, 100);
  }
  EXPECT_EQ(server_->files_on_card(), 0u) << "delete_after_download left files on the card";
}

TEST_F(Gphoto2PtpipTest, IsoAndApertureSettingsFromRigYamlReachTheCamera) {
  rig::Gphoto2Options options = Options();
  options.iso = "400";
  options.aperture = "5.6";  // matches the widget's "f/5.6"
  rig::Gphoto2Camera camera(options);
  EXPECT_EQ(server_->exposure().iso, 400);
  EXPECT_NEAR(server_->exposure().f_number, 5.6, 1e-9);
  const auto settings = camera.CurrentSettings();
  EXPECT_NE(std::find(settings.begin(), settings.end(),
                      std::pair<std::string, std::string>{"f-number", "f/5.6"}),
            settings.end());
}

TEST_F(Gphoto2PtpipTest, BusyCameraIsRetriedWithBackoffAndTheShotIsDownloaded) {
  rig::Gphoto2Camera camera(Options());
  camera.SetExposure(1.0 / 250);
  server_->InjectFaults({.busy_responses = 3});
  const std::vector<rig::Frame> frames = camera.Capture();
  EXPECT_EQ(frames.size(), 2u);
  EXPECT_EQ(server_->counters().busy, 3);
  EXPECT_EQ(server_->files_on_card(), 0u);
}

TEST_F(Gphoto2PtpipTest, CameraBusyLongerThanTheRetriesIsABusyError) {
  rig::Gphoto2Camera camera(Options());
  server_->InjectFaults({.busy_responses = 100});
  const std::string message = ExpectError([&] { camera.Capture(); }, Kind::kBusy);
  EXPECT_NE(message.find("busy"), std::string::npos) << message;
  EXPECT_EQ(server_->counters().busy, 5);  // busy_attempts, then it gives up
}

// libgphoto2 2.5.30 turns a busy answer to a single setting into "bad parameters" (and its
// whole-tree set_config can even report success): the shot must not be taken with an exposure
// the camera refused. On a network camera the refusal closes the session (kGone).
TEST_F(Gphoto2PtpipTest, RefusedExposureSettingIsGoneNotAShotWithTheOldExposure) {
  rig::Gphoto2Camera camera(Options());
  server_->InjectFaults({.busy_settings = 1});
  const std::string message = ExpectError([&] { camera.SetExposure(1.0 / 60); }, Kind::kGone);
  EXPECT_NE(message.find("was refused"), std::string::npos) << message;
  EXPECT_NEAR(server_->exposure().exposure_s, 0.004, 1e-9);  // unchanged
  camera.Reopen();
  EXPECT_NEAR(camera.SetExposure(1.0 / 60), 0.0167, 1e-9);  // the next try is taken
  EXPECT_NEAR(server_->exposure().exposure_s, 0.0167, 1e-9);
}

TEST_F(Gphoto2PtpipTest, ClosingAPtpipCameraLeavesDescriptorZeroAlone) {
  const int before = fcntl(0, F_GETFD);
  { rig::Gphoto2Camera camera(Options()); }
  EXPECT_EQ(fcntl(0, F_GETFD), before) << "libgphoto2's PTP/IP disconnect closed descriptor 0";
}

TEST_F(Gphoto2PtpipTest, FullCardIsAStorageFullErrorAndTheCardKeepsItsFiles) {
  rig::Gphoto2Options options = Options();
  options.delete_after_download = false;
  rig::Gphoto2Camera camera(options);
  server_->InjectFaults({.card_capacity_files = 2});  // one RAW+JPEG pair
  EXPECT_EQ(camera.Capture().size(), 2u);
  const std::string message = ExpectError([&] { camera.Capture(); }, Kind::kStorageFull);
  EXPECT_NE(message.find("delete_after_download"), std::string::npos) << message;
  EXPECT_EQ(server_->counters().store_full, 1);
  EXPECT_EQ(server_->files_on_card(), 2u);
  EXPECT_FALSE(CameraError(Kind::kStorageFull, 0, "").recoverable());
}

TEST_F(Gphoto2PtpipTest, ConnectionDroppedDuringADownloadIsGoneAndReopenGetsTheNextShot) {
  rig::Gphoto2Camera camera(Options());
  server_->InjectFaults({.drop_downloads = 1});
  const std::string message = ExpectError([&] { camera.Capture(); }, Kind::kGone);
  EXPECT_NE(message.find("lost the network connection"), std::string::npos) << message;
  EXPECT_EQ(server_->counters().dropped, 1);
  // The camera is closed, so nothing reads a stale answer; the owner reopens and shoots again.
  ExpectError([&] { camera.SetExposure(1.0 / 60); }, Kind::kGone);
  camera.Reopen();
  EXPECT_EQ(camera.Capture().size(), 2u);
  EXPECT_EQ(server_->counters().connections, 2);
  // The interrupted shot's files are still on the card: nothing was deleted unread.
  EXPECT_EQ(server_->files_on_card(), 2u);
}

TEST_F(Gphoto2PtpipTest, SlowCameraWithinTheLinkTimeoutStillCaptures) {
  rig::Gphoto2Camera camera(Options());
  server_->InjectFaults({.response_delay_s = 0.2});
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(camera.Capture().size(), 2u);
  EXPECT_GT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(1000));
}

TEST_F(Gphoto2PtpipTest, CameraSilentBeyondTheLinkTimeoutIsGoneAndReopenRecovers) {
  rig::Gphoto2Camera camera(Options());
  server_->InjectFaults({.response_delay_s = 3.0});  // libgphoto2 waits 2.5 s per read
  ExpectError([&] { camera.SetExposure(1.0 / 60); }, Kind::kGone);
  server_->InjectFaults({});
  // The camera finishes its stalled answer first; until then a reopen times out too, and the
  // owner tries again after a pause (as the run engine and RecoverCamera do).
  int attempts = 0;
  for (bool open = false; !open && attempts < 4; ++attempts) {
    try {
      camera.Reopen();
      open = true;
    } catch (const CameraError& e) {
      EXPECT_TRUE(e.recoverable()) << e.what();
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
  }
  EXPECT_LE(attempts, 2);
  EXPECT_NEAR(camera.SetExposure(1.0 / 60), 0.0167, 1e-9);
  EXPECT_EQ(camera.Capture().size(), 2u);
}

TEST_F(Gphoto2PtpipTest, CameraThatVanishesIsGoneUntilItIsBackThenReopenWorks) {
  rig::Gphoto2Camera camera(Options());
  camera.SetExposure(1.0 / 60);
  server_->InjectFaults({.vanish_s = 1.5});
  const auto vanished = std::chrono::steady_clock::now();
  ExpectError([&] { camera.Capture(); }, Kind::kGone);
  // While it is away the port refuses connections: reopening fails, recoverably.
  try {
    camera.Reopen();
    if (std::chrono::steady_clock::now() - vanished < std::chrono::milliseconds(1400)) {
      ADD_FAILURE() << "reopened a camera that is away";
    }
  } catch (const CameraError& e) {
    EXPECT_TRUE(e.recoverable()) << e.what();
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1600));
  camera.Reopen();
  // The exposure set before the camera vanished is applied again by Reopen().
  EXPECT_NEAR(server_->exposure().exposure_s, 0.0167, 1e-9);
  EXPECT_EQ(camera.Capture().size(), 2u);
  EXPECT_EQ(server_->counters().vanished, 1);
}

}  // namespace
}  // namespace brdfrig::simcamera
