// The pose from the marker mask (issue 24 item 3) against the simulator's truth: the rig file a
// capture carries is the scene's own rig, so a position's camera_disagreement_m is the measured
// camera centre's distance from the true one.
#include <gtest/gtest.h>

#include <iostream>

#include "reconstruct/pipeline.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

using testing::SceneSpec;
using testing::SimulateCapture;

constexpr const char* kMarkerMask =
    "{cutout: [0.1, 0.1], paper: [0.3, 0.3], paper_albedo: 0.8, markers: {}}";

SceneSpec MirrorLikeSample() {
  SceneSpec spec;
  // A sharp, bright lobe: the highlight reaches the cut-out's edge at the mirror position.
  spec.brdf = "{model: ggx, alpha: 0.05, f0: [0.9, 0.8, 0.7], diffuse: 0.02}";
  spec.positions = "[{camera_arm: 20, light_arm: -20}, {camera_arm: 40, light_arm: -40}]";
  spec.supersampling = 4;
  return spec;
}

std::filesystem::path TempDir(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("brdfrig_marker_pose_" + name);
}

TEST(MarkerPoseTest, TheMarkerMaskGivesThePoseFromItsCornersAtEveryPosition) {
  SceneSpec spec = MirrorLikeSample();
  spec.target = kMarkerMask;
  const CaptureSet capture = SimulateCapture(TempDir("markers"), spec);
  const ReconstructionResult result = Reconstruct(capture, testing::SeedOnly());
  std::cout << result.Summary();
  ASSERT_EQ(result.positions.size(), 2u);
  for (const PositionReport& p : result.positions) {
    SCOPED_TRACE("position " + std::to_string(p.index));
    ASSERT_TRUE(p.used) << p.skipped_reason;
    EXPECT_EQ(p.pose_from, "markers");
    // The default ring holds 16 markers (5 a row, 3 a column): every one is found.
    EXPECT_EQ(p.pose_points, 4 * 16);
    // Measured: 0.18 and 0.26 px RMS, the camera centre 0.14 and 0.38 mm from the truth.
    EXPECT_LT(p.reprojection_rms_px, 0.5);
    EXPECT_LT(p.camera_disagreement_m, 1e-3);
    for (const std::string& w : p.warnings) EXPECT_EQ(w.find("pose from the cut-out"), w.npos) << w;
  }
}

TEST(MarkerPoseTest, ThePaperBetweenCutoutAndRingCalibratesLikeAPlainMask) {
  // The markers' ink must not reach the paper's radiometry: the scale k from the marker mask
  // equals the plain mask's (same light, same camera) to a fraction of a percent.
  SceneSpec plain = MirrorLikeSample();
  SceneSpec marked = plain;
  marked.target = kMarkerMask;
  const ReconstructionResult a =
      Reconstruct(SimulateCapture(TempDir("plain"), plain), testing::SeedOnly());
  const ReconstructionResult b =
      Reconstruct(SimulateCapture(TempDir("marked"), marked), testing::SeedOnly());
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(b.positions[i].radiometry.scale[c] / a.positions[i].radiometry.scale[c], 1.0,
                  3e-3)
          << "position " << i << " channel " << c;
    }
  }
}

TEST(MarkerPoseTest, ARigThatExpectsMarkersOnAPlainMaskFallsBackToTheCutoutAndSaysSo) {
  SceneSpec spec = MirrorLikeSample();
  const CaptureSet plain = SimulateCapture(TempDir("expects"), spec);
  CaptureSet capture = plain;
  capture.nominal.target.markers = geometry::MaskMarkerRing{};
  const ReconstructionResult result = Reconstruct(capture, testing::SeedOnly());
  for (const PositionReport& p : result.positions) {
    ASSERT_TRUE(p.used) << p.skipped_reason;
    EXPECT_EQ(p.pose_from, "cut-out");
    EXPECT_EQ(p.pose_points, 4);
    bool said = false;
    for (const std::string& w : p.warnings) {
      said = said || w.find("0 of the marker mask's markers found") != w.npos;
    }
    EXPECT_TRUE(said) << "no warning that the markers were not found";
  }
}

}  // namespace
}  // namespace brdfrig::reconstruct
