// Sessions end to end on the simulated rig: what a capture records, how it reads back, how
// names are guarded, what `session verify` finds, and the session-time model.
#include <gtest/gtest.h>

#include <fstream>

#include "acquire/capture.h"
#include "acquire/session_store.h"
#include "common/atomic_file.h"
#include "common/sha256.h"
#include "session/session_reader.h"
#include "session/session_verify.h"
#include "tests/acquire/test_rig.h"

namespace brdfrig::acquire {

using session::ReadSession;
using session::RecordedFrame;
using session::SessionContents;
using session::VerifyReport;
using session::VerifySession;

namespace {

constexpr double kDegree = M_PI / 180;

CaptureOptions Options(const testing::TestRig& rig, const std::string& name) {
  CaptureOptions options;
  options.rig_file = rig.rig_file;
  options.plan_file = rig.plan_file;
  options.output_dir = rig.sessions / name;
  return options;
}

TEST(SessionTest, CaptureRecordsEveryFrameAndReadsBackThroughReadSession) {
  const auto rig = testing::MakeTestRig("session_capture");
  const CaptureSummary summary = RunCapture(Options(rig, "s1"));
  ASSERT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
  EXPECT_EQ(summary.run.frames_recorded, 6);

  const SessionContents s = ReadSession(rig.sessions / "s1");
  EXPECT_EQ(s.name, "s1");
  EXPECT_EQ(s.sample, "test-sample");
  EXPECT_EQ(s.operator_name, "tester");
  EXPECT_EQ(s.notes, "acquisition test");
  EXPECT_FALSE(s.software_version.empty());
  EXPECT_EQ(s.exit_status, "success");
  ASSERT_EQ(s.planned_positions.size(), 3u);
  EXPECT_NEAR(s.planned_positions[2].at("camera_arm"), 50 * kDegree, 1e-12);
  ASSERT_EQ(s.planned_brackets.size(), 3u);
  EXPECT_EQ(s.planned_brackets[0], (std::vector<double>{0.001, 0.01}));
  EXPECT_NE(s.rig.geometry.FindAxis("light_arm"), nullptr);
  EXPECT_EQ(s.rig.geometry.intrinsics.width, 64);
  EXPECT_TRUE(s.Complete());
  ASSERT_EQ(s.frames.size(), 6u);
  for (std::size_t i = 0; i < s.frames.size(); ++i) {
    const RecordedFrame& f = s.frames[i];
    EXPECT_EQ(f.position_index, static_cast<int>(i / 2));
    EXPECT_EQ(f.bracket_index, static_cast<int>(i % 2));
    EXPECT_EQ(Sha256FileHex(f.file), f.sha256);
    EXPECT_NEAR(f.axis_readings.at("camera_arm"),
                s.planned_positions[f.position_index].at("camera_arm"), 1e-9);
    EXPECT_DOUBLE_EQ(f.requested_exposure_s, s.planned_brackets[0][f.bracket_index]);
    EXPECT_DOUBLE_EQ(f.exposure_s, f.requested_exposure_s);  // offered shutter speeds
    EXPECT_GE(f.saturated_fraction, 0);
  }
  EXPECT_EQ(s.frames[3].file.filename(), "p001_b1.png");
  // The snapshot makes the session self-contained.
  EXPECT_TRUE(std::filesystem::exists(s.dir / "rig" / "rig.yaml"));
  EXPECT_TRUE(std::filesystem::exists(s.dir / "rig" / "scene.yaml"));
  EXPECT_TRUE(std::filesystem::exists(s.dir / "plan.yaml"));
  EXPECT_TRUE(VerifySession(s.dir).ok()) << VerifySession(s.dir).ToString();
}

TEST(SessionTest, NamesThatEscapeOrHideAreRefusedAndSessionsAreNeverOverwritten) {
  for (const std::string& bad :
       std::vector<std::string>{"", "..", ".", "../x", "a/b", ".hidden", "a..b", "-x", "a b",
                                "a\\b", std::string(101, 'a')}) {
    EXPECT_FALSE(IsValidSessionName(bad)) << bad;
  }
  for (const std::string& good : std::vector<std::string>{"s1", "2026-11-29_tile.A", "x"}) {
    EXPECT_TRUE(IsValidSessionName(good)) << good;
  }
  const auto rig = testing::MakeTestRig("session_names");
  CaptureOptions traversal = Options(rig, "x");
  traversal.output_dir = rig.sessions / "..";
  EXPECT_THROW(RunCapture(traversal), Error);
  ASSERT_EQ(RunCapture(Options(rig, "once")).run.status, ExitStatus::kSuccess);
  try {
    RunCapture(Options(rig, "once"));
    FAIL() << "an existing session was reused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("already exists"), std::string::npos) << e.what();
  }
}

TEST(SessionTest, ASessionHasOneWriterAtATime) {
  const auto rig = testing::MakeTestRig("session_lock");
  // A trailing slash names the same session.
  CaptureOptions options = Options(rig, "locked");
  options.output_dir = rig.sessions / "locked/";
  ASSERT_EQ(RunCapture(options).run.status, ExitStatus::kSuccess);
  const auto first = SessionStore::Open(rig.sessions / "locked");
  try {
    SessionStore::Open(rig.sessions / "locked");
    FAIL() << "a second writer opened the session";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
  }
  // Readers are not writers: reading and verifying work meanwhile.
  EXPECT_EQ(ReadSession(rig.sessions / "locked").frames.size(), 6u);
  EXPECT_TRUE(VerifySession(rig.sessions / "locked").ok());
}

TEST(SessionTest, VerifyFindsMissingExtraAndChangedFiles) {
  const auto rig = testing::MakeTestRig("session_verify");
  ASSERT_EQ(RunCapture(Options(rig, "v")).run.status, ExitStatus::kSuccess);
  const auto dir = rig.sessions / "v";
  std::filesystem::remove(dir / "frames" / "p000_b0.png");
  std::ofstream(dir / "frames" / "p001_b0.png", std::ios::app) << "x";
  std::ofstream(dir / "frames" / "stray.png") << "x";
  const VerifyReport report = VerifySession(dir);
  EXPECT_FALSE(report.ok());
  EXPECT_EQ(report.checked, 6);
  EXPECT_EQ(report.missing, std::vector<std::string>{"frames/p000_b0.png"});
  EXPECT_EQ(report.changed, std::vector<std::string>{"frames/p001_b0.png"});
  EXPECT_EQ(report.extra, std::vector<std::string>{"frames/stray.png"});
}

TEST(SessionTest, ResumingACompleteSessionCapturesNothingMore) {
  const auto rig = testing::MakeTestRig("session_resume_done");
  ASSERT_EQ(RunCapture(Options(rig, "r")).run.status, ExitStatus::kSuccess);
  CaptureOptions again = Options(rig, "r");
  again.resume = true;
  const CaptureSummary summary = RunCapture(again);
  EXPECT_TRUE(summary.resumed);
  EXPECT_EQ(summary.run.status, ExitStatus::kSuccess);
  EXPECT_EQ(summary.run.frames_recorded, 0);
  EXPECT_EQ(ReadSession(rig.sessions / "r").frames.size(), 6u);
}

TEST(SessionTest, ResumingWithAChangedRigFileIsRecordedAsAWarning) {
  const auto rig = testing::MakeTestRig("session_rig_changed");
  ASSERT_EQ(RunCapture(Options(rig, "r")).run.status, ExitStatus::kSuccess);
  std::ofstream(rig.rig_file, std::ios::app) << "# drive replaced\n";
  CaptureOptions again = Options(rig, "r");
  again.resume = true;
  const CaptureSummary summary = RunCapture(again);
  ASSERT_EQ(summary.warnings.size(), 1u);
  EXPECT_NE(summary.warnings[0].find("rig.yaml changed since the session started"),
            std::string::npos)
      << summary.warnings[0];
  // The session keeps the rig it started with.
  EXPECT_EQ(ReadFileToString(rig.sessions / "r" / "rig" / "rig.yaml"), testing::RigYaml());
}

TEST(SessionTest, ResumingWithADifferentPlanIsRefused) {
  const auto rig = testing::MakeTestRig("session_resume_other_plan");
  ASSERT_EQ(RunCapture(Options(rig, "r")).run.status, ExitStatus::kSuccess);
  std::ofstream(rig.dir / "other.yaml") << "sample: other\npositions:\n  - {camera_arm: 20}\n";
  CaptureOptions again = Options(rig, "r");
  again.resume = true;
  again.plan_file = rig.dir / "other.yaml";
  EXPECT_THROW(RunCapture(again), Error);
}

TEST(SessionTest, AutoBracketKeepsTheHighlightUnsaturatedInTheShortestExposure) {
  const auto rig = testing::MakeTestRig("session_auto", "", R"(sample: auto
positions:
  - {camera_arm: 30, light_arm: -30}
exposures: {auto: {count: 3, metering_s: 0.01}}
settle_s: 0
)");
  const CaptureSummary summary = RunCapture(Options(rig, "a"));
  ASSERT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
  const SessionContents s = ReadSession(rig.sessions / "a");
  ASSERT_EQ(s.frames.size(), 3u);
  ASSERT_EQ(s.planned_brackets[0].size(), 3u);
  EXPECT_LT(s.planned_brackets[0][0], s.planned_brackets[0][2]);
  EXPECT_EQ(s.frames[0].saturated_fraction, 0);
  EXPECT_TRUE(s.Complete());
}

// A dark sample under bright paper: metering the paper alone exposed it for the paper, and the
// sample read below the reconstruction's noise floor. The bracket now stretches until the
// sample's median reads at 1 % of full scale; the camera takes it and records what it took.
TEST(SessionTest, AutoBracketExposesADarkSampleLongerThanThePaperNeeds) {
  const std::string plan = R"(sample: auto
positions:
  - {camera_arm: 30, light_arm: -30}
exposures: {auto: {count: 3, metering_s: 0.01}}
settle_s: 0
)";
  std::vector<double> longest;
  for (const char* brdf :
       {"{model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}", "{model: lambert, albedo: 0.002}"}) {
    std::string scene = testing::SmallSceneYaml();
    const std::string bright = "brdf: {model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}";
    scene.replace(scene.find(bright), bright.size(), std::string("brdf: ") + brdf);
    const std::string shutter = "shutter_speeds: [0.001, 0.01, 0.1]";
    scene.replace(scene.find(shutter), shutter.size(),
                  "shutter_speeds: [0.001, 0.01, 0.1, 0.25, 0.5, 1, 2, 4, 8]");
    const auto rig = testing::MakeTestRig("session_auto_dark", "", plan);
    std::ofstream(rig.dir / "scene.yaml") << scene;
    const CaptureSummary summary = RunCapture(Options(rig, "a"));
    ASSERT_EQ(summary.run.status, ExitStatus::kSuccess) << summary.ToString();
    const SessionContents s = ReadSession(rig.sessions / "a");
    ASSERT_EQ(s.planned_brackets[0].size(), 3u);
    longest.push_back(s.planned_brackets[0].back());
    EXPECT_LE(s.frames.back().exposure_s, 8) << brdf;
  }
  // Paper at 0.7, the dark sample at 0.002: the paper's exposure leaves it at about 0.1 % of
  // full scale, the floor itself; the metered bracket goes about ten times longer.
  EXPECT_GT(longest[1], 5 * longest[0]) << longest[0] << " s, " << longest[1] << " s";
}

TEST(SessionTest, OverlappedRecordingIsCloserToTheUnavoidableTimeThanSerial) {
  const auto rig = testing::MakeTestRig("session_timing");
  CaptureOptions overlapped = Options(rig, "overlapped");
  const RunSummary fast = RunCapture(overlapped).run;
  CaptureOptions serial = Options(rig, "serial");
  serial.run.overlap = false;
  const RunSummary slow = RunCapture(serial).run;
  ASSERT_EQ(fast.status, ExitStatus::kSuccess);
  ASSERT_EQ(slow.status, ExitStatus::kSuccess);
  // Same device work either way.
  EXPECT_NEAR(fast.timing.unavoidable_s, slow.timing.unavoidable_s, 1e-9);
  EXPECT_GE(fast.timing.Ratio(), 1.0 - 1e-9);
  EXPECT_LT(fast.timing.Ratio(), 1.05) << fast.ToString();
  // Serial: every frame's checking and recording adds to the session. Overlapped: only what
  // the moves and shots that follow could not hide (the last frame's at least, not all).
  EXPECT_NEAR(slow.timing.session_s - slow.timing.unavoidable_s, slow.timing.host_s, 1e-6)
      << slow.ToString();
  EXPECT_LT(fast.timing.session_s - fast.timing.unavoidable_s, fast.timing.host_s)
      << fast.ToString();
  EXPECT_GT(fast.timing.session_s - fast.timing.unavoidable_s, 0);
}

}  // namespace
}  // namespace brdfrig::acquire
