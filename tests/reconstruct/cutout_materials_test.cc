// The cut-out is found on every measured material: simulated captures (realistic 14-bit sensor,
// three exposures merged to HDR) of all 27 nbrdf materials at mirror, off-specular, near-retro
// and out-of-plane positions; corners within a pixel of the truth and the pose close to it,
// starting from a nominal pose a few millimetres and half a degree off.
#include <gtest/gtest.h>

#include <cstdio>
#include <iostream>
#include <mutex>

#include "brdf/nbrdf_library.h"
#include "common/parallel.h"
#include "reconstruct/hdr_merge.h"
#include "reconstruct/target.h"
#include "sim/scene.h"
#include "sim/simulator.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

constexpr double kDeg = M_PI / 180;

struct Position {
  double camera_arm, light_arm, light_azimuth;  // degrees
};

// Four of the default plan's mirror positions, off-specular ones (the highlight off the cut-out's
// centre or outside it), a near-retro-reflection one and two with the light out of the plane.
const std::vector<Position> kPositions = {{15, -15, 0}, {35, -35, 0}, {55, -55, 0}, {65, -65, 0},
                                          {30, -10, 0}, {10, -40, 0}, {30, 25, 0},  {35, -35, 90}};

struct Outcome {
  bool found = false;
  std::string error;
  double corner_px = 0;     // worst corner's distance to the true projection
  double reprojection = 0;  // EstimatePose's RMS
  double centre_mm = 0;     // camera centre error
  double rotation_deg = 0;  // camera orientation error
  int cutout_edges = 0;
};

Outcome Measure(const sim::Simulator& simulator, const Position& p, int index) {
  const geometry::RigGeometry& rig = simulator.scene().rig;
  const geometry::AxisPositions at = {{"camera_arm", p.camera_arm * kDeg},
                                 {"light_arm", p.light_arm * kDeg},
                                 {"light_azimuth", p.light_azimuth * kDeg}};
  sim::RenderOptions render;
  render.threads = 1;
  const cv::Mat radiance = simulator.RenderRadiance(at, render);
  std::vector<cv::Mat> photos;
  for (std::size_t e = 0; e < simulator.scene().capture.exposures.size(); ++e) {
    photos.push_back(
        simulator.Expose(radiance, simulator.scene().capture.exposures[e], 100 * index + e, 1));
  }
  HdrMergeOptions merge;
  merge.threads = 1;
  const HdrImage hdr = MergeBracket(photos, simulator.scene().capture.exposures, cv::Mat(), merge);

  const geometry::CameraPose truth = rig.CameraAt(at);
  geometry::CameraPose nominal = truth;  // a real rig is a few mm and half a degree off
  nominal.camera_from_world.translate(geometry::Vec3(0.004, -0.003, 0.002) * (index % 2 ? 1 : -1));
  nominal.camera_from_world.rotate(Eigen::AngleAxisd(0.5 * kDeg, geometry::Vec3(1, 1, 0).normalized()));
  Outcome out;
  try {
    const TargetOptions options;
    const TargetCorners corners =
        FindCutoutCorners(hdr.radiance, hdr.valid, rig.intrinsics, nominal, rig.target, options);
    const PoseEstimate pose = EstimatePose(corners, rig.intrinsics, rig.target, nominal, options);
    const double w = rig.target.cutout_width / 2, h = rig.target.cutout_height / 2;
    const geometry::Vec3 world[4] = {{-w, -h, 0}, {w, -h, 0}, {w, h, 0}, {-w, h, 0}};
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector2d want;
      if (!geometry::ProjectToPixel(rig.intrinsics, truth, world[k], &want)) continue;
      out.corner_px = std::max(out.corner_px, std::hypot(corners.corners[k].x - want.x(),
                                                         corners.corners[k].y - want.y()));
    }
    out.reprojection = pose.reprojection_rms_px;
    out.centre_mm = 1e3 * (pose.pose.CenterInWorld() - truth.CenterInWorld()).norm();
    const Eigen::Matrix3d r =
        pose.pose.camera_from_world.linear() * truth.camera_from_world.linear().transpose();
    out.rotation_deg = Eigen::AngleAxisd(r).angle() / kDeg;
    out.cutout_edges = corners.cutout_edges_found;
    out.found = true;
  } catch (const Error& e) {
    out.error = e.what();
  }
  return out;
}

TEST(CutoutOnMeasuredMaterials, FoundInEveryPositionOnEveryMaterial) {
  const std::vector<std::string> names = brdf::NbrdfMaterialNames();
  ASSERT_EQ(names.size(), 27u);
  std::vector<std::unique_ptr<sim::Simulator>> simulators;
  for (const std::string& name : names) {
    testing::SceneSpec spec;
    spec.brdf = "{model: nbrdf, name: " + name + "}";
    spec.supersampling = 4;  // edges exact to ~0.1 px
    spec.effects =
        "[{type: shot_noise, full_well: 30000}, {type: read_noise, sigma: 0.0005}, "
        "{type: saturation, level: 1.0}, {type: quantization, bits: 14}]";
    simulators.push_back(std::make_unique<sim::Simulator>(
        sim::LoadSceneString(testing::SceneYaml(spec), name + ".yaml")));
  }
  const std::size_t cases = names.size() * kPositions.size();
  std::vector<Outcome> outcomes(cases);
  ParallelFor(cases, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t m = i / kPositions.size(), p = i % kPositions.size();
      outcomes[i] = Measure(*simulators[m], kPositions[p], static_cast<int>(i));
    }
  });

  std::printf("%-26s %5s %9s %9s %9s %9s %6s\n", "material", "found", "corner_px", "reproj_px",
              "centre_mm", "rot_deg", "fallbk");
  for (std::size_t m = 0; m < names.size(); ++m) {
    Outcome worst;
    int found = 0, fallback = 0;
    for (std::size_t p = 0; p < kPositions.size(); ++p) {
      const Outcome& o = outcomes[m * kPositions.size() + p];
      const Position& at = kPositions[p];
      if (!o.found) {
        ADD_FAILURE() << names[m] << " at camera_arm " << at.camera_arm << ", light_arm "
                      << at.light_arm << ", light_azimuth " << at.light_azimuth << ": " << o.error;
        continue;
      }
      ++found;
      fallback += o.cutout_edges < 4;
      EXPECT_LT(o.corner_px, 1.0) << names[m] << " position " << p;
      EXPECT_LT(o.reprojection, 1.0) << names[m] << " position " << p;
      EXPECT_LT(o.centre_mm, 5.0) << names[m] << " position " << p;
      EXPECT_LT(o.rotation_deg, 0.5) << names[m] << " position " << p;
      worst.corner_px = std::max(worst.corner_px, o.corner_px);
      worst.reprojection = std::max(worst.reprojection, o.reprojection);
      worst.centre_mm = std::max(worst.centre_mm, o.centre_mm);
      worst.rotation_deg = std::max(worst.rotation_deg, o.rotation_deg);
    }
    std::printf("%-26s %2d/%-2zu %9.3f %9.3f %9.2f %9.3f %6d\n", names[m].c_str(), found,
                kPositions.size(), worst.corner_px, worst.reprojection, worst.centre_mm,
                worst.rotation_deg, fallback);
  }
}

}  // namespace
}  // namespace brdfrig::reconstruct
