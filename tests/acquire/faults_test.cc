// Every injected fault ends in its documented outcome (docs/acquire.md, fault policy), and
// nothing recorded is ever lost: camera gone and back, camera gone for good, camera busy,
// axis alarm, Modbus timeout on a real Modbus drive (simulated server), disk full; plus the
// operator's pause, resume and abort.
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "acquire/capture.h"
#include "acquire/test_hooks.h"
#include "common/sha256.h"
#include "rig/drive_profile.h"
#include "rig/hardware_backends.h"
#include "session/session_reader.h"
#include "session/session_verify.h"
#include "session/sqlite_db.h"
#include "sim/modbus_drive_server.h"
#include "tests/acquire/test_rig.h"

namespace brdfrig::acquire {

using session::ReadSession;
using session::RecordedFrame;
using session::SessionContents;
using session::SqliteDb;
using session::Statement;
using session::VerifyReport;
using session::VerifySession;

namespace {

namespace fs = std::filesystem;

CaptureOptions Options(const testing::TestRig& rig, const std::string& name) {
  CaptureOptions options;
  options.rig_file = rig.rig_file;
  options.plan_file = rig.plan_file;
  options.output_dir = rig.sessions / name;
  options.run.retry.initial_backoff_s = 0.001;  // the policy, not the waiting, is under test
  options.run.retry.max_attempts = 3;
  return options;
}

std::vector<std::string> Events(const fs::path& session) {
  SqliteDb db(session / "session.sqlite", SqliteDb::Mode::kReadOnly);
  Statement q(db, "SELECT message FROM events ORDER BY id");
  std::vector<std::string> events;
  while (q.Step()) events.push_back(q.Text(0));
  return events;
}

bool AnyEventHas(const fs::path& session, const std::string& text) {
  for (const std::string& e : Events(session)) {
    if (e.find(text) != std::string::npos) return true;
  }
  return false;
}

// Every recorded frame is intact and the folder holds nothing else.
void ExpectIntact(const fs::path& session) {
  const SessionContents s = ReadSession(session);
  for (const RecordedFrame& f : s.frames) EXPECT_EQ(Sha256FileHex(f.file), f.sha256);
  const VerifyReport report = VerifySession(session);
  EXPECT_TRUE(report.ok()) << report.ToString();
}

void ExpectCompleteAfterResume(const testing::TestRig& rig, const std::string& name) {
  CaptureOptions resume = Options(rig, name);
  resume.resume = true;
  const CaptureSummary summary = RunCapture(resume);
  EXPECT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
  const SessionContents s = ReadSession(rig.sessions / name);
  EXPECT_TRUE(s.Complete());
  EXPECT_EQ(s.frames.size(), 6u);
  ExpectIntact(rig.sessions / name);
}

TEST(FaultsTest, CameraGoneAndBackIsReopenedAndTheShotRetried) {
  // Gone after 3 shots; the first Reopen fails, the second finds it.
  const auto rig = testing::MakeTestRig(
      "fault_gone", "faults:\n  - {type: camera_disconnect, after_shots: 3, reopen_failures: 1}\n");
  const CaptureSummary summary = RunCapture(Options(rig, "s"));
  ASSERT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
  EXPECT_EQ(summary.run.retries, 2);
  EXPECT_EQ(summary.run.frames_recorded, 6);
  EXPECT_TRUE(AnyEventHas(rig.sessions / "s", "camera re-opened"));
  ExpectIntact(rig.sessions / "s");
}

TEST(FaultsTest, CameraGoneForGoodFailsAfterBoundedRetriesKeepsFramesAndResumes) {
  const auto rig = testing::MakeTestRig(
      "fault_gone_for_good",
      "faults:\n  - {type: camera_disconnect, after_shots: 3, reopen_failures: 100}\n");
  const CaptureSummary summary = RunCapture(Options(rig, "s"));
  EXPECT_EQ(summary.run.status, ExitStatus::kFailed);
  EXPECT_NE(summary.run.reason.find("gave up after 3 attempts"), std::string::npos)
      << summary.run.reason;
  const SessionContents s = ReadSession(rig.sessions / "s");
  EXPECT_EQ(s.exit_status, "failed");
  EXPECT_EQ(s.frames.size(), 3u);  // position 0 complete, position 1's first shot
  ExpectIntact(rig.sessions / "s");
  // The camera is plugged back in (the scene without the fault): the session completes.
  std::ofstream(rig.dir / "scene.yaml") << testing::SmallSceneYaml();
  ExpectCompleteAfterResume(rig, "s");
}

TEST(FaultsTest, BusyCameraIsRetriedAfterABackOff) {
  const auto rig = testing::MakeTestRig("fault_busy",
                                        "faults:\n  - {type: camera_busy, at_shot: 2, count: 2}\n");
  const CaptureSummary summary = RunCapture(Options(rig, "s"));
  ASSERT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
  EXPECT_EQ(summary.run.retries, 2);
  EXPECT_EQ(ReadSession(rig.sessions / "s").frames.size(), 6u);
  ExpectIntact(rig.sessions / "s");
}

TEST(FaultsTest, AxisAlarmIsResetAndTheMoveRetried) {
  const auto rig = testing::MakeTestRig(
      "fault_alarm", "faults:\n  - {type: axis_alarm, axis: light_arm, at_move: 2}\n");
  const CaptureSummary summary = RunCapture(Options(rig, "s"));
  ASSERT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
  EXPECT_EQ(summary.run.retries, 1);
  EXPECT_TRUE(AnyEventHas(rig.sessions / "s", "axis 'light_arm': alarm reset"));
  const SessionContents s = ReadSession(rig.sessions / "s");
  ASSERT_EQ(s.frames.size(), 6u);
  EXPECT_NEAR(s.frames[2].axis_readings.at("light_arm"), s.planned_positions[1].at("light_arm"),
              1e-9);
  ExpectIntact(rig.sessions / "s");
}

TEST(FaultsTest, ModbusTimeoutOnARealDriveClientIsRetried) {
  sim::ModbusDriveServer drive(rig::LoadDriveProfile("generic"), {});
  auto rig = testing::MakeTestRig("fault_modbus");
  rig::RegisterHardwareBackends();
  // light_arm is a Modbus drive on loopback TCP; the rest stays simulated.
  std::ofstream(rig.rig_file) << "geometry: scene.yaml\n"
                                 "camera: {backend: sim, scene: scene.yaml}\n"
                                 "axes:\n"
                                 "  camera_arm: {backend: sim, scene: scene.yaml}\n"
                                 "  light_arm: {backend: modbus, transport: tcp, host: 127.0.0.1, "
                                 "port: " +
                                     std::to_string(drive.port()) +
                                     ", profile: generic, timeout_ms: 50, attempts: 2, "
                                     "speed_deg_s: 2000, accel_deg_s2: 40000, min_deg: -80, "
                                     "max_deg: 80, poll_ms: 2}\n";
  CaptureOptions options = Options(rig, "s");
  options.on_engine = [&drive](RunEngine* e) {
    if (e == nullptr) return;
    sim::DriveFaults faults;
    faults.drop_responses = 3;  // the first move times out on both attempts of the link
    drive.InjectFaults(faults);
  };
  const CaptureSummary summary = RunCapture(options);
  ASSERT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
  EXPECT_GE(summary.run.retries, 1);
  EXPECT_GE(drive.counters().dropped, 3);
  EXPECT_TRUE(AnyEventHas(rig.sessions / "s", "axis:"));
  const SessionContents s = ReadSession(rig.sessions / "s");
  ASSERT_EQ(s.frames.size(), 6u);
  EXPECT_NEAR(s.frames[5].axis_readings.at("light_arm"), s.planned_positions[2].at("light_arm"),
              0.001);
  ExpectIntact(rig.sessions / "s");
}

TEST(FaultsTest, DiskFullFailsTheRunKeepsWhatWasRecordedAndResumes) {
  const auto rig = testing::MakeTestRig("fault_disk_full");
  test_hooks::SetFailWriteAt(4);
  const CaptureSummary summary = RunCapture(Options(rig, "s"));
  test_hooks::SetFailWriteAt(0);
  EXPECT_EQ(summary.run.status, ExitStatus::kFailed);
  EXPECT_NE(summary.run.reason.find("No space left on device"), std::string::npos)
      << summary.run.reason;
  const SessionContents s = ReadSession(rig.sessions / "s");
  EXPECT_EQ(s.exit_status, "failed");
  EXPECT_EQ(s.frames.size(), 3u);  // frames 1-3 recorded, the 4th could not be written
  ExpectIntact(rig.sessions / "s");
  ExpectCompleteAfterResume(rig, "s");
}

TEST(FaultsTest, FramesFailingTheirCheckRedoThePositionThenFailWithNothingRecorded) {
  // A sensor so insensitive that every frame is black (as with the lens cap on).
  std::string scene = testing::SmallSceneYaml();
  scene.replace(scene.find("gain: 10"), 8, "gain: 0.0001");
  const auto rig = testing::MakeTestRig("fault_black");
  std::ofstream(rig.dir / "scene.yaml") << scene;
  const CaptureSummary summary = RunCapture(Options(rig, "s"));
  EXPECT_EQ(summary.run.status, ExitStatus::kFailed);
  EXPECT_NE(summary.run.reason.find("keep failing their check"), std::string::npos)
      << summary.run.reason;
  // Each position is redone at most RetryPolicy::max_position_redos (2) times; how many
  // positions were captured before the first rejection came back depends on the writer.
  EXPECT_GE(summary.run.redos, 2);
  EXPECT_LE(summary.run.redos, 6);
  EXPECT_TRUE(AnyEventHas(rig.sessions / "s", "all black"));
  EXPECT_TRUE(ReadSession(rig.sessions / "s").frames.empty());
  ExpectIntact(rig.sessions / "s");
}

TEST(FaultsTest, PauseStopsAtASafePointResumeContinuesAbortEndsResumably) {
  const auto rig = testing::MakeTestRig("operator_controls");
  CaptureOptions options = Options(rig, "s");
  RunEngine* engine = nullptr;
  bool paused_seen = false, aborted = false;
  options.on_engine = [&](RunEngine* e) {
    engine = e;
    if (e != nullptr) e->Pause();  // pauses at the first safe point, before any move
  };
  options.on_progress = [&](const RunProgress& p) {
    if (p.state == RunState::kPaused && !paused_seen) {
      paused_seen = true;
      EXPECT_EQ(p.frames_recorded, 0);
      // Resume from another thread, as the daemon's API would.
      std::thread([engine] { engine->Resume(); }).detach();
    }
    if (p.state == RunState::kAcquiring && p.position == 1 && !aborted) {
      aborted = true;
      engine->Abort("operator abort in test");
    }
  };
  const CaptureSummary summary = RunCapture(options);
  EXPECT_TRUE(paused_seen);
  EXPECT_EQ(summary.run.status, ExitStatus::kAborted);
  EXPECT_EQ(summary.run.reason, "operator abort in test");
  const SessionContents s = ReadSession(rig.sessions / "s");
  EXPECT_EQ(s.exit_status, "aborted");
  EXPECT_EQ(s.frames.size(), 2u);  // position 0, recorded although the run was aborted
  ExpectIntact(rig.sessions / "s");
  ExpectCompleteAfterResume(rig, "s");
}

}  // namespace
}  // namespace brdfrig::acquire
