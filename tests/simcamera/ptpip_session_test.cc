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

#include "reconstruct/raw_photo.h"
#include "session/session_reader.h"
#include "session/session_verify.h"
#include "tests/acquire/test_rig.h"
#include "tests/simcamera/loopback_lab.h"

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
    lab_ = std::make_unique<LoopbackLab>(dir_, acquire::testing::SmallSceneYaml(),
                                         acquire::testing::SmallPlanYaml(),
                                         std::vector<double>{0.001, 0.01, 0.1});
  }

  void TearDown() override {
    lab_.reset();
    fs::remove_all(dir_);
  }

  acquire::CaptureSummary Capture(const std::string& name) { return lab_->Capture(name); }
  PtpIpCameraServer& camera() { return lab_->camera(); }

  // Checks a finished session: complete, verified, a DNG and a JPEG per shot, each DNG the
  // simulator's image at the axis readings the session recorded for it.
  void ExpectCompleteAndTrue(const fs::path& session_dir) {
    const session::VerifyReport verify = session::VerifySession(session_dir);
    EXPECT_TRUE(verify.ok()) << verify.ToString();
    const session::SessionContents s = session::ReadSession(session_dir);
    EXPECT_EQ(s.exit_status, "success");
    EXPECT_TRUE(s.Complete());
    ASSERT_EQ(s.frames.size(), 12u);  // 3 positions × 2 exposures × (JPEG + DNG)
    const sim::Simulator truth(lab_->renderer().scene());
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
  std::unique_ptr<LoopbackLab> lab_;
};

TEST_F(PtpipSessionTest, CaptureThroughHardwareBackendsRecordsTheSceneAtTheDrivesPositions) {
  const acquire::CaptureSummary summary = Capture("clean");
  ASSERT_EQ(summary.run.status, acquire::ExitStatus::kSuccess) << summary.ToString();
  ExpectCompleteAndTrue(dir_ / "sessions" / "clean");
  EXPECT_EQ(camera().counters().captures, 6);
  EXPECT_EQ(camera().files_on_card(), 0u);
}

TEST_F(PtpipSessionTest, BusyAndDroppedDownloadsAreRetriedAndNothingIsLost) {
  camera().InjectFaults({.busy_responses = 2, .drop_downloads = 1});
  const acquire::CaptureSummary summary = Capture("faults");
  ASSERT_EQ(summary.run.status, acquire::ExitStatus::kSuccess) << summary.ToString();
  EXPECT_GE(summary.run.retries, 1);
  ExpectCompleteAndTrue(dir_ / "sessions" / "faults");
  EXPECT_EQ(camera().counters().busy, 2);
  EXPECT_EQ(camera().counters().dropped, 1);
  EXPECT_EQ(camera().counters().captures, 7);  // the shot whose download broke is retaken
}

TEST_F(PtpipSessionTest, CameraThatVanishesIsReopenedWhenBackAndTheSessionCompletes) {
  camera().InjectFaults({.vanish_s = 1.0});
  const acquire::CaptureSummary summary = Capture("vanish");
  ASSERT_EQ(summary.run.status, acquire::ExitStatus::kSuccess) << summary.ToString();
  ExpectCompleteAndTrue(dir_ / "sessions" / "vanish");
  EXPECT_EQ(camera().counters().vanished, 1);
  EXPECT_GE(camera().counters().connections, 2);
}

TEST_F(PtpipSessionTest, FullCardStopsTheSessionAsFailedAndKeepsWhatWasRecorded) {
  lab_->WriteRig(false);  // files stay on the card, which holds three RAW+JPEG shots
  camera().InjectFaults({.card_capacity_files = 6});
  const acquire::CaptureSummary summary = Capture("full");
  EXPECT_EQ(summary.run.status, acquire::ExitStatus::kFailed) << summary.ToString();
  EXPECT_NE(summary.ToString().find("memory card"), std::string::npos) << summary.ToString();
  EXPECT_EQ(camera().counters().store_full, 1);  // not retried: retrying cannot free space
  const session::VerifyReport verify = session::VerifySession(dir_ / "sessions" / "full");
  EXPECT_TRUE(verify.ok()) << verify.ToString();
  const session::SessionContents s = session::ReadSession(dir_ / "sessions" / "full");
  EXPECT_EQ(s.frames.size(), 6u);  // the three shots taken before the card was full
}

}  // namespace
}  // namespace brdfrig::simcamera
