// A capture whose rig.yaml references a lens calibration keeps a copy in the session's rig
// snapshot, and the session reads back with the calibrated intrinsics of that copy, whatever
// happens to the lab's file afterwards (issue 24): the reconstruction of a session uses the
// lens as it was calibrated when the session was captured.
#include <gtest/gtest.h>

#include <fstream>

#include "acquire/capture.h"
#include "geometry/lens_calibration_file.h"
#include "session/session_reader.h"
#include "tests/acquire/test_rig.h"

namespace brdfrig::acquire {
namespace {

geometry::LensCalibration Calibration(double fx) {
  geometry::LensCalibration c;
  c.created = "2026-12-02T10:00:00Z";
  c.intrinsics = {64, 48, fx, fx - 0.5, 32.5, 23.0, -0.05, 0.01};
  return c;
}

TEST(SessionLensCalibrationTest, SessionReadsBackWithItsSnapshotOfTheLensCalibration) {
  const testing::TestRig rig = testing::MakeTestRig("session_lens_calibration");
  geometry::WriteLensCalibration(rig.dir / "lens.json", Calibration(81.0));
  std::ofstream(rig.rig_file, std::ios::app) << "calibration: {lens: lens.json}\n";
  CaptureOptions options;
  options.rig_file = rig.rig_file;
  options.plan_file = rig.plan_file;
  options.output_dir = rig.sessions / "calibrated";
  ASSERT_EQ(RunCapture(options).run.status, ExitStatus::kSuccess);
  // The lab recalibrates later: the session keeps what it was captured with.
  geometry::WriteLensCalibration(rig.dir / "lens.json", Calibration(90.0));

  const session::SessionContents s = session::ReadSession(options.output_dir);
  EXPECT_DOUBLE_EQ(s.rig.geometry.intrinsics.fx, 81.0);
  EXPECT_DOUBLE_EQ(s.rig.geometry.intrinsics.fy, 80.5);
  EXPECT_DOUBLE_EQ(s.rig.geometry.intrinsics.cx, 32.5);
  EXPECT_DOUBLE_EQ(s.rig.geometry.intrinsics.k1, -0.05);
  EXPECT_EQ(s.rig.calibration.lens.parent_path(), options.output_dir / "rig");
}

}  // namespace
}  // namespace brdfrig::acquire
