// Reconstruction from an acquisition session: the run engine captures with simulated devices
// into a session directory, and the reconstruction reads it back through acquire::ReadSession.
#include <gtest/gtest.h>

#include <fstream>

#include "acquire/capture.h"
#include "common/exr_io.h"
#include "common/sha256.h"
#include "geometry/light_calibration_file.h"
#include "reconstruct/batch.h"
#include "reconstruct/pipeline.h"
#include "rig/rig_file.h"
#include "sim/devices.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

namespace fs = std::filesystem;

struct SessionSetup {
  fs::path dir;
  acquire::CaptureOptions capture;
};

// scene.yaml (an ideal sensor, the slice-model truth), rig.yaml with every device simulated,
// and plan.yaml with three positions of three exposures.
SessionSetup MakeSession(const std::string& name, const testing::SceneSpec& scene = {}) {
  SessionSetup s;
  s.dir = fs::temp_directory_path() / ("brdfrig_session_capture_" + name);
  fs::remove_all(s.dir);
  fs::create_directories(s.dir);
  brdf::WriteMaterialFile(s.dir / "truth.json", testing::FlatSliceTruth());
  std::ofstream(s.dir / "scene.yaml") << testing::SceneYaml(scene);
  std::ofstream(s.dir / "rig.yaml") << "geometry: scene.yaml\n"
                                       "camera: {backend: sim, scene: scene.yaml}\n"
                                       "axes:\n"
                                       "  camera_arm: {backend: sim, scene: scene.yaml}\n"
                                       "  light_arm: {backend: sim, scene: scene.yaml}\n";
  std::ofstream(s.dir / "plan.yaml") << "sample: flat-slices\n"
                                        "positions:\n"
                                        "  - {camera_arm: 20, light_arm: -20}\n"
                                        "  - {camera_arm: 35, light_arm: -35}\n"
                                        "  - {camera_arm: 50, light_arm: -50}\n"
                                        "exposures: [0.001, 0.008, 0.0666667]\n"
                                        "settle_s: 0\n";
  sim::RegisterSimBackends();
  s.capture.rig_file = s.dir / "rig.yaml";
  s.capture.plan_file = s.dir / "plan.yaml";
  s.capture.output_dir = s.dir / "session";
  return s;
}

TEST(SessionCapture, IdealSessionIsRecoveredToOnePartInAThousand) {
  SessionSetup s = MakeSession("ideal");
  ASSERT_EQ(acquire::RunCapture(s.capture).run.status, acquire::ExitStatus::kSuccess);
  ASSERT_TRUE(IsCaptureDirectory(s.dir / "session"));
  const CaptureSet capture = LoadCapture(s.dir / "session");
  EXPECT_TRUE(capture.warnings.empty());
  ASSERT_EQ(capture.positions.size(), 3u);
  for (const CapturePosition& p : capture.positions) EXPECT_EQ(p.frames.size(), 3u);
  EXPECT_NEAR(capture.positions[1].axis_readings.at("camera_arm"), 35 * M_PI / 180, 1e-9);

  const ReconstructionResult result = Reconstruct(capture, testing::SeedOnly());
  ASSERT_EQ(result.material.slices.size(), 3u);
  const brdf::Material truth = testing::FlatSliceTruth();
  const brdf::Slice& want = truth.slices[0];
  for (const brdf::Slice& slice : result.material.slices) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(slice.channel[c].a1, want.channel[c].a1, 1e-3 * want.channel[c].a1);
      EXPECT_NEAR(slice.channel[c].h, want.channel[c].h, 1e-3 * want.channel[c].h);
    }
  }
}

TEST(SessionCapture, AbortedSessionUsesItsCompletePositionsAndSaysSo) {
  SessionSetup s = MakeSession("aborted");
  // Abort once the second position has its first frame: position 0 complete, 1 partial. The
  // trigger is the engine's own step (it publishes each frame's index before it shoots it, and
  // checks for an abort before every shot), not the count of recorded frames: the writer
  // records on its own thread, and on a loaded machine it fell behind until every position had
  // been shot before the fourth frame was recorded.
  acquire::RunEngine* engine = nullptr;
  s.capture.on_engine = [&](acquire::RunEngine* e) { engine = e; };
  s.capture.on_progress = [&](const acquire::RunProgress& p) {
    if (p.position == 1 && p.frame == 1 && engine) engine->Abort("test stops the run");
  };
  acquire::RunCapture(s.capture);
  const CaptureSet capture = LoadCapture(s.dir / "session");
  ASSERT_GE(capture.positions.size(), 1u);
  EXPECT_LT(capture.positions.size(), 3u);
  ASSERT_FALSE(capture.warnings.empty());
  EXPECT_NE(capture.warnings[0].find("aborted"), std::string::npos) << capture.warnings[0];
  for (const CapturePosition& p : capture.positions) EXPECT_EQ(p.frames.size(), 3u);
  const ReconstructionResult result = Reconstruct(capture, testing::SeedOnly());
  EXPECT_EQ(result.material.slices.size(), capture.positions.size());
  EXPECT_EQ(result.warnings.front(), capture.warnings.front());
}

// The gain of the scene's polynomial vignetting (sim/sensor.cc) at every pixel, scaled to mean 1
// as `brdfrig rig calibrate flat` writes its maps.
cv::Mat TrueGainMap(const geometry::Intrinsics& k, double a1, double a2) {
  cv::Mat gain(k.height, k.width, CV_32FC3);
  const double half_diagonal2 = 0.25 * (k.width * k.width + k.height * k.height);
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const double r2 = ((x - k.cx) * (x - k.cx) + (y - k.cy) * (y - k.cy)) / half_diagonal2;
      gain.at<cv::Vec3f>(y, x) = cv::Vec3f::all(static_cast<float>(1 + a1 * r2 + a2 * r2 * r2));
    }
  }
  return gain / cv::mean(gain)[0];
}

// 30 % vignetting with a fourth-order fall-off, which the paper's own quadratic field
// (radiometry.h) cannot follow: without the flat field the levels are off by percents, with it
// they are as exact as the ideal camera's; material.json names the map it used and says which
// values stayed nominal.
TEST(SessionCapture, FlatFieldCalibrationUndoesTheCamerasVignetting) {
  testing::SceneSpec scene;
  scene.effects = "[{type: vignetting, falloff: polynomial, a1: -0.1, a2: -0.2}]";
  SessionSetup plain = MakeSession("vignetted", scene);
  ASSERT_EQ(acquire::RunCapture(plain.capture).run.status, acquire::ExitStatus::kSuccess);
  const CaptureSet uncalibrated = LoadCapture(plain.dir / "session");
  const ReconstructionResult nominal = Reconstruct(uncalibrated, testing::SeedOnly());

  SessionSetup s = MakeSession("flat_calibrated", scene);
  WriteRadianceExr(s.dir / "flat.exr", TrueGainMap(uncalibrated.nominal.intrinsics, -0.1, -0.2));
  std::ofstream(s.dir / "rig.yaml", std::ios::app) << "calibration: {flat: flat.exr}\n";
  ASSERT_EQ(acquire::RunCapture(s.capture).run.status, acquire::ExitStatus::kSuccess);
  const CaptureSet capture = LoadCapture(s.dir / "session");
  ASSERT_TRUE(capture.calibration.has_value());
  EXPECT_EQ(capture.calibration->flat.parent_path(), s.dir / "session" / "rig");
  const ReconstructionResult calibrated = Reconstruct(capture, testing::SeedOnly());

  const double without = testing::WorstSliceError(nominal.material, testing::FlatSliceTruth());
  const double with = testing::WorstSliceError(calibrated.material, testing::FlatSliceTruth());
  std::printf("worst level error: %.4f %% without the flat field, %.4f %% with it\n", 100 * without,
              100 * with);
  EXPECT_LT(with, 2e-3);
  EXPECT_GT(without, 5 * with);

  const nlohmann::json& used = calibrated.material.provenance.at("calibration");
  EXPECT_EQ(used.at("flat").at("sha256"), Sha256FileHex(s.dir / "flat.exr"));
  EXPECT_EQ(used.at("lens"), "nominal");
  EXPECT_EQ(nominal.material.provenance.at("calibration").at("flat"), "nominal");
  bool said = false;
  for (const std::string& w : calibrated.warnings) {
    said = said || w.find("nominal values for: lens, white reference") != std::string::npos;
  }
  EXPECT_TRUE(said) << "no warning that the lens and white reference are nominal";
}

// A calibrated light is taken as measured: no position moves it to its highlight, material.json
// says where each position's light came from, and the fit is as exact as the ideal session's.
TEST(SessionCapture, CalibratedLightIsUsedAsMeasured) {
  SessionSetup s = MakeSession("light_calibrated");
  geometry::LightCalibration light;
  light.created = "2026-12-03T09:00:00Z";
  light.light_position = rig::ReadRigDescription(s.dir / "rig.yaml").geometry.light_position;
  geometry::WriteLightCalibration(s.dir / "light.json", light);
  std::ofstream(s.dir / "rig.yaml", std::ios::app) << "calibration: {light: light.json}\n";
  ASSERT_EQ(acquire::RunCapture(s.capture).run.status, acquire::ExitStatus::kSuccess);
  const CaptureSet capture = LoadCapture(s.dir / "session");
  ASSERT_TRUE(capture.calibration.has_value());
  EXPECT_EQ(capture.calibration->light.filename(), "light.json");
  const ReconstructionResult result = Reconstruct(capture, testing::SeedOnly());
  const nlohmann::json& provenance = result.material.provenance;
  ASSERT_EQ(provenance.at("positions").size(), 3u);
  for (const nlohmann::json& p : provenance.at("positions")) {
    EXPECT_EQ(p.at("light_from"), "calibration") << p.dump();
    EXPECT_EQ(p.at("light_refinement_deg"), 0.0) << p.dump();
  }
  EXPECT_EQ(provenance.at("calibration").at("light").at("sha256"),
            Sha256FileHex(s.dir / "light.json"));
  const double error = testing::WorstSliceError(result.material, testing::FlatSliceTruth());
  std::printf("worst level error with the calibrated light: %.4f %%\n", 100 * error);
  EXPECT_LT(error, 1e-3);
}

}  // namespace
}  // namespace brdfrig::reconstruct
