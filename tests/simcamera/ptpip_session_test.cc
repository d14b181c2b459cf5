// A whole capture through the hardware backends only, every device a simulated process on
// loopback: the gphoto2 camera over libgphoto2's PTP/IP transport to the simulated network
// camera, the axes over libmodbus TCP to two simulated drives. The camera photographs the pose
// it reads from the same drives over Modbus, so each recorded photo must be the simulator's
// image at the axis readings the session recorded. Camera faults during the run must end in a
// complete session with nothing recorded lost (`session verify` clean).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>

#include "acquire/capture.h"
#include "reconstruct/raw_photo.h"
#include "rig/drive_profile.h"
#include "rig/hardware_backends.h"
#include "session/session_reader.h"
#include "session/session_verify.h"
#include "sim/modbus_drive_server.h"
#include "simcamera/drive_positions.h"
#include "simcamera/ptpip_server.h"
#include "simcamera/shot_renderer.h"
#include "tests/acquire/test_rig.h"

extern "C" const char* __lsan_default_suppressions() {
  return "leak:libgphoto2.so\nleak:libgphoto2_port.so\nleak:libltdl.so\n";
}
extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }

namespace brdfrig::simcamera {
namespace {

namespace fs = std::filesystem;

class PtpipSessionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("brdfrig_ptpip_session_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "sessions");
    setenv("HOME", dir_.c_str(), 1);  // libgphoto2's ~/.gphoto/settings
    rig::RegisterHardwareBackends();
    std::ofstream(dir_ / "scene.yaml") << acquire::testing::SmallSceneYaml();
    std::ofstream(dir_ / "plan.yaml") << acquire::testing::SmallPlanYaml();

    const rig::DriveProfile profile = rig::LoadDriveProfile("generic");
    for (const char* axis : {"camera_arm", "light_arm"}) {
      drives_[axis] = std::make_unique<sim::ModbusDriveServer>(profile, sim::DriveServerOptions{});
    }
    // The drives' positions are read over Modbus, from the rig file written below (its axes
    // connect on their first request, at the first shot).
    renderer_ = std::make_shared<ShotRenderer>(
        sim::LoadScene(dir_ / "scene.yaml"),
        [this] {
          std::lock_guard lock(positions_mutex_);
          if (!positions_) positions_ = std::make_unique<DrivePositions>(dir_ / "rig.yaml");
          return positions_->Read();
        },
        2);
    camera_ = std::make_unique<PtpIpCameraServer>(
        CameraServerOptions{.offer = {.shutter_speeds_s = {0.001, 0.01, 0.1}}},
        [renderer = renderer_](const ExposureSettings& e) { return renderer->Shoot(e); });
    WriteRig(true);
  }

  void WriteRig(bool delete_after_download) {
    std::ofstream(dir_ / "rig.yaml")
        << "geometry: scene.yaml\n"
        << "camera: {backend: gphoto2, port: \"" << camera_->PortPath()
        << "\", delete_after_download: " << (delete_after_download ? "true" : "false")
        << ", event_drain_s: 0.5, timeout_s: 20}\n"
        << "axes:\n"
        << DriveLine("camera_arm") << DriveLine("light_arm");
  }

  void TearDown() override {
    camera_.reset();
    positions_.reset();
    fs::remove_all(dir_);
  }

  std::string DriveLine(const std::string& axis) const {
    return "  " + axis + ": {backend: modbus, transport: tcp, host: 127.0.0.1, port: " +
           std::to_string(drives_.at(axis)->port()) +
           ", slave: 1, profile: generic, steps_per_degree: 100, speed_deg_s: 400, "
           "accel_deg_s2: 4000}\n";
  }

  acquire::CaptureSummary Capture(const std::string& name) {
    acquire::CaptureOptions options;
    options.rig_file = dir_ / "rig.yaml";
    options.plan_file = dir_ / "plan.yaml";
    options.output_dir = dir_ / "sessions" / name;
    options.run.retry.initial_backoff_s = 0.3;
    return acquire::RunCapture(options);
  }

  // Checks a finished session: complete, verified, a DNG and a JPEG per shot, each DNG the
  // simulator's image at the axis readings the session recorded for it.
  void ExpectCompleteAndTrue(const fs::path& session_dir) {
    const session::VerifyReport verify = session::VerifySession(session_dir);
    EXPECT_TRUE(verify.ok()) << verify.ToString();
    const session::SessionContents s = session::ReadSession(session_dir);
    EXPECT_EQ(s.exit_status, "success");
    EXPECT_TRUE(s.Complete());
    ASSERT_EQ(s.frames.size(), 12u);  // 3 positions × 2 exposures × (JPEG + DNG)
    const sim::Simulator truth(renderer_->scene());
    int dngs = 0;
    for (const session::RecordedFrame& f : s.frames) {
      if (f.file.extension() != ".dng") continue;
      ++dngs;
      const cv::Mat photo = reconstruct::ReadRawPhoto(f.file);
      cv::Mat expected = truth.RenderCameraImage(f.axis_readings, f.exposure_s, 0);
      for (int c = 0; c < 3; ++c) {  // every channel: the DNG keeps the sensor's colours
        const double photo_mean = cv::mean(photo)[c] / 65535;
        const double expected_mean = cv::mean(cv::min(expected, 1.0))[c];
        EXPECT_NEAR(photo_mean, expected_mean, 0.01 * expected_mean + 1e-4)
            << f.file << " channel " << c << " is not the scene at its recorded axis readings";
      }
      EXPECT_NEAR(f.axis_readings.at("camera_arm"),
                  s.planned_positions[f.position_index].at("camera_arm"), 0.001);
    }
    EXPECT_EQ(dngs, 6);
  }

  fs::path dir_;
  std::map<std::string, std::unique_ptr<sim::ModbusDriveServer>> drives_;
  std::mutex positions_mutex_;
  std::unique_ptr<DrivePositions> positions_;
  std::shared_ptr<ShotRenderer> renderer_;
  std::unique_ptr<PtpIpCameraServer> camera_;
};

TEST_F(PtpipSessionTest, CaptureThroughHardwareBackendsRecordsTheSceneAtTheDrivesPositions) {
  const acquire::CaptureSummary summary = Capture("clean");
  ASSERT_EQ(summary.run.status, acquire::ExitStatus::kSuccess) << summary.ToString();
  ExpectCompleteAndTrue(dir_ / "sessions" / "clean");
  EXPECT_EQ(camera_->counters().captures, 6);
  EXPECT_EQ(camera_->files_on_card(), 0u);
}

TEST_F(PtpipSessionTest, BusyAndDroppedDownloadsAreRetriedAndNothingIsLost) {
  camera_->InjectFaults({.busy_responses = 2, .drop_downloads = 1});
  const acquire::CaptureSummary summary = Capture("faults");
  ASSERT_EQ(summary.run.status, acquire::ExitStatus::kSuccess) << summary.ToString();
  EXPECT_GE(summary.run.retries, 1);
  ExpectCompleteAndTrue(dir_ / "sessions" / "faults");
  EXPECT_EQ(camera_->counters().busy, 2);
  EXPECT_EQ(camera_->counters().dropped, 1);
  EXPECT_EQ(camera_->counters().captures, 7);  // the shot whose download broke is retaken
}

TEST_F(PtpipSessionTest, CameraThatVanishesIsReopenedWhenBackAndTheSessionCompletes) {
  camera_->InjectFaults({.vanish_s = 1.0});
  const acquire::CaptureSummary summary = Capture("vanish");
  ASSERT_EQ(summary.run.status, acquire::ExitStatus::kSuccess) << summary.ToString();
  ExpectCompleteAndTrue(dir_ / "sessions" / "vanish");
  EXPECT_EQ(camera_->counters().vanished, 1);
  EXPECT_GE(camera_->counters().connections, 2);
}

TEST_F(PtpipSessionTest, FullCardStopsTheSessionAsFailedAndKeepsWhatWasRecorded) {
  WriteRig(false);  // files stay on the card, which holds three RAW+JPEG shots
  camera_->InjectFaults({.card_capacity_files = 6});
  const acquire::CaptureSummary summary = Capture("full");
  EXPECT_EQ(summary.run.status, acquire::ExitStatus::kFailed) << summary.ToString();
  EXPECT_NE(summary.ToString().find("memory card"), std::string::npos) << summary.ToString();
  EXPECT_EQ(camera_->counters().store_full, 1);  // not retried: retrying cannot free space
  const session::VerifyReport verify = session::VerifySession(dir_ / "sessions" / "full");
  EXPECT_TRUE(verify.ok()) << verify.ToString();
  const session::SessionContents s = session::ReadSession(dir_ / "sessions" / "full");
  EXPECT_EQ(s.frames.size(), 6u);  // the three shots taken before the card was full
}

}  // namespace
}  // namespace brdfrig::simcamera
