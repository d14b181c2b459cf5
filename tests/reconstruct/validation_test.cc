// Validation positions never reach the fit; a designed plan observes, in a simulated capture,
// the (θh, θd) cells the designer claims.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "acquire/capture.h"
#include "brdf/material_file.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "coverage/coverage.h"
#include "reconstruct/pipeline.h"
#include "session/session_reader.h"
#include "sim/devices.h"
#include "sim/scene.h"
#include "sim/simulator.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

namespace fs = std::filesystem;

std::string FitOf(const CaptureSet& capture, ReconstructionResult* result) {
  ReconstructOptions options;
  *result = Reconstruct(capture, options);
  const fs::path file = fs::temp_directory_path() / "validation_fit.json";
  brdf::WriteMaterialFile(file, result->material);
  return ReadFileToString(file);
}

// Each rung's fitted model without its scores and provenance: what the fit made of its photos.
std::vector<std::string> RungModels(const ReconstructionResult& result) {
  std::vector<std::string> out;
  for (const RungResult& rung : result.ladder.rungs) {
    if (!rung.fitted) continue;
    brdf::Material m = rung.material;
    m.ladder = nlohmann::json::array();
    m.provenance = nlohmann::json::object();
    out.push_back(brdf::SerializeMaterial(m));
  }
  return out;
}

TEST(ValidationTest, ValidationPhotosNeverReachTheFit) {
  testing::SceneSpec spec;
  spec.width = 320;
  spec.height = 240;
  spec.supersampling = 4;
  spec.positions =
      "[{camera_arm: 20, light_arm: -20}, {camera_arm: 40, light_arm: -40}, "
      "{camera_arm: 30, light_arm: -10, validation: true}]";
  const brdf::Material truth = testing::FlatSliceTruth();
  const CaptureSet capture =
      testing::SimulateCapture(fs::temp_directory_path() / "validation", spec, &truth);
  ASSERT_EQ(capture.positions.size(), 3u);
  EXPECT_FALSE(capture.positions[0].validation);
  EXPECT_TRUE(capture.positions[2].validation);

  ReconstructionResult first;
  FitOf(capture, &first);
  ASSERT_EQ(first.validation.size(), 1u);
  EXPECT_EQ(first.validation[0].index, 2);
  EXPECT_EQ(first.validation[0].frames.size(), 3u);
  EXPECT_NEAR(first.validation[0].axis_readings.at("light_arm"), Radians(-10), 1e-9);
  // The validation position is measured only to score the ladder's rungs on it.
  for (const RungResult& rung : first.ladder.rungs) {
    EXPECT_EQ(rung.validation_scores.size(), 1u) << brdf::ModelKindName(rung.kind);
  }

  // Corrupt every validation photo: were any of its pixels read by a fit, that rung's model
  // would fail or change. Every rung's model is byte-identical; only the scores lose the
  // validation position (it can no longer be measured, and says so).
  for (const BracketFrame& frame : capture.positions[2].frames) {
    WriteFileAtomically(frame.file, "not a photo");
  }
  ReconstructionResult second;
  FitOf(capture, &second);
  EXPECT_EQ(second.validation.size(), 1u);
  EXPECT_EQ(RungModels(second), RungModels(first));
  for (const RungResult& rung : second.ladder.rungs) EXPECT_TRUE(rung.validation_scores.empty());
  bool reported = false;
  for (const PositionReport& p : second.positions) reported |= p.index == 2 && !p.used;
  EXPECT_TRUE(reported) << "the unreadable validation position is reported as skipped";
}

TEST(ValidationTest, SimulatedCaptureOfADesignedPlanObservesWhatTheDesignerClaims) {
  testing::SceneSpec spec;
  spec.width = 320;
  spec.height = 240;
  spec.positions = "{design: {count: 6, validation: 1}}";
  spec.brdf = "{model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}";
  const fs::path dir = fs::temp_directory_path() / "designed";
  fs::create_directories(dir);
  WriteFileAtomically(dir / "scene.yaml", testing::SceneYaml(spec));
  const sim::Scene scene = sim::LoadScene(dir / "scene.yaml");
  ASSERT_EQ(scene.capture.positions.size(), 7u);
  EXPECT_TRUE(scene.capture.validation[6]);
  const coverage::CoverageMap claimed =
      coverage::ComputeCoverage(scene.rig, scene.capture.positions, scene.capture.validation);
  const sim::Simulator simulator(scene.Ideal());
  const coverage::GridOptions grid;
  for (std::size_t p = 0; p < scene.capture.positions.size(); ++p) {
    // The simulator's own geometry, pixel by pixel: every image pixel whose ray meets the
    // sample plane inside the cut-out, with the true light and camera.
    const sim::TrueGeometry g = simulator.GeometryAt(scene.capture.positions[p]);
    const geometry::Vec3 camera = g.camera.CenterInWorld();
    std::set<int> seen;
    for (int v = 0; v < g.intrinsics.height; ++v) {
      for (int u = 0; u < g.intrinsics.width; ++u) {
        const geometry::Vec3 ray = geometry::PixelRayInWorld(g.intrinsics, g.camera, {u, v});
        if (ray.z() >= 0) continue;
        const geometry::Vec3 x = camera + (-camera.z() / ray.z()) * ray;
        if (std::abs(x.x()) > scene.rig.target.cutout_width / 2 ||
            std::abs(x.y()) > scene.rig.target.cutout_height / 2) {
          continue;
        }
        const coverage::HalfDiff hd =
            coverage::ToHalfDiff((g.light_position - x).normalized(), (camera - x).normalized());
        seen.insert(coverage::ThetaHBin(hd.theta_h, grid.theta_h_bins) * grid.theta_d_bins +
                    coverage::ThetaDBin(hd.theta_d, grid.theta_d_bins));
      }
    }
    const std::vector<int>& cells = claimed.positions[p].cells;
    const std::set<int> predicted(cells.begin(), cells.end());
    ASSERT_FALSE(seen.empty()) << "position " << p << ": the cut-out is not in the image";
    int agree = 0;
    for (const int c : seen) agree += predicted.count(c);
    // The pixels and the designer's cut-out points sample the same patch: the cells agree but
    // for a few on the patch's border (one, on a patch of fewer than ten cells: a 320 x 240
    // image may not reach a border cell that the designer's points touch).
    const auto few = [](std::size_t n) { return std::min(0.9 * n, n - 1.0); };
    EXPECT_GE(agree, few(seen.size())) << "position " << p;
    EXPECT_GE(agree, few(predicted.size())) << "position " << p;
  }
}

TEST(ValidationTest, SessionRecordsTheRoleAndTheCaptureSetCarriesIt) {
  const fs::path dir = fs::temp_directory_path() / "validation_session";
  fs::remove_all(dir);
  fs::create_directories(dir);
  testing::SceneSpec spec;
  spec.width = 320;
  spec.height = 240;
  spec.supersampling = 2;
  spec.brdf = "{model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}";
  WriteFileAtomically(dir / "scene.yaml", testing::SceneYaml(spec));
  WriteFileAtomically(dir / "rig.yaml",
                      "geometry: scene.yaml\ncamera: {backend: sim, scene: scene.yaml}\naxes:\n"
                      "  camera_arm: {backend: sim, scene: scene.yaml}\n"
                      "  light_arm: {backend: sim, scene: scene.yaml}\n"
                      "light: {backend: sim, scene: scene.yaml}\n");
  WriteFileAtomically(dir / "plan.yaml",
                      "sample: s\npositions:\n  - {camera_arm: 20, light_arm: -20}\n"
                      "  - {camera_arm: 30, light_arm: -10, validation: true}\n"
                      "exposures: [0.008]\nsettle_s: 0\n");
  sim::RegisterSimBackends();
  acquire::CaptureOptions options;
  options.rig_file = dir / "rig.yaml";
  options.plan_file = dir / "plan.yaml";
  options.output_dir = dir / "session";
  ASSERT_EQ(acquire::RunCapture(options).run.status, acquire::ExitStatus::kSuccess);
  const session::SessionContents contents = session::ReadSession(dir / "session");
  EXPECT_EQ(contents.planned_validation, (std::vector<bool>{false, true}));
  const CaptureSet capture = LoadSessionCapture(dir / "session");
  ASSERT_EQ(capture.positions.size(), 2u);
  EXPECT_FALSE(capture.positions[0].validation);
  EXPECT_TRUE(capture.positions[1].validation);
}

}  // namespace
}  // namespace brdfrig::reconstruct
