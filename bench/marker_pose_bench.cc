// The pose from the marker mask against the pose from the cut-out's corners, on the measured
// materials (issue 24 item 3). For each material: the default scene (its noise, its sensor)
// with the rig's target a marker mask, captured at every position of the designed plan; each
// position measured twice from the same photos, once with the rig's markers (the pose from the
// markers' corners) and once without (the cut-out's four), each camera centre against the
// simulator's truth. Prints a per-material table and the distribution over all positions.
//
//   bench_marker_pose [--measured-dir DIR] [--positions 6] [--width 1600 --height 1200]
//                     [--every N] [--work DIR]
//
// --every N takes every Nth material (sorted by name), so a subset still spans the sources.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/format.h"
#include "jobs/material_study.h"
#include "jobs/study.h"
#include "reconstruct/capture_set.h"
#include "reconstruct/measure_position.h"
#include "sim/simulate.h"

namespace {

using namespace brdfrig;
namespace fs = std::filesystem;

struct Args {
  fs::path measured_dir = fs::path(BRDFRIG_SOURCE_DIR) / "data/materials/nbrdf";
  fs::path work = fs::temp_directory_path() / "brdfrig_marker_pose_bench";
  int positions = 6, width = 1600, height = 1200, every = 1;
};

struct PoseError {
  bool found = false;
  double camera_mm = 0;  // measured centre to the true one
  double rms_px = 0;
  int points = 0;
  std::string error;
};

PoseError Measure(const reconstruct::CapturePosition& position, geometry::RigGeometry rig,
                  bool markers) {
  if (!markers) rig.target.markers.reset();
  PoseError e;
  try {
    reconstruct::MeasureState state;
    const reconstruct::MeasuredPosition m =
        reconstruct::MeasurePosition(position, rig, reconstruct::MeasureOptions{}, &state);
    e.found = m.report.pose_from == (markers ? "markers" : "cut-out");
    e.camera_mm = 1e3 * m.report.camera_disagreement_m;
    e.rms_px = m.report.reprojection_rms_px;
    e.points = m.report.pose_points;
  } catch (const std::exception& ex) {
    e.error = ex.what();
  }
  return e;
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5))];
}

int Run(const Args& a) {
  std::vector<jobs::StudyMaterial> materials = jobs::MeasuredStudyMaterials(a.measured_dir);
  std::vector<jobs::StudyMaterial> chosen;
  for (std::size_t i = 0; i < materials.size(); i += a.every) chosen.push_back(materials[i]);
  if (chosen.empty()) throw Error("no measured materials in " + a.measured_dir.string());
  const jobs::StudyPlan plan = jobs::DesignedPlan(a.positions);
  std::printf(
      "Marker-mask pose vs cut-out pose: %zu materials, %s, %d×%d, the default scene's "
      "noise; camera-centre error against the simulator's truth (mm)\n\n",
      chosen.size(), plan.name.c_str(), a.width, a.height);
  std::printf(
      "| material | markers: median / worst mm | corners (min) | cut-out: median / worst mm "
      "| positions the cut-out failed |\n| --- | ---: | ---: | ---: | ---: |\n");
  std::vector<double> all_markers, all_cutout;
  int marker_fallbacks = 0, cutout_failures = 0, total = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const jobs::StudyMaterial& material : chosen) {
    jobs::StudySettings s;
    s.width = a.width;
    s.height = a.height;
    s.sample_brdf = material.brdf_yaml;
    auto scene = std::make_shared<sim::Scene>(
        jobs::StudyScene(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml", s));
    scene->rig.target.markers = geometry::MaskMarkerRing{};
    const fs::path dir = a.work / material.name;
    fs::remove_all(dir);
    sim::SimulateOptions options;
    options.scene = fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml";
    options.loaded_scene = scene;
    options.output_dir = dir;
    options.positions = plan.positions;
    options.write_truth = false;
    sim::Simulate(options);
    const reconstruct::CaptureSet capture = reconstruct::LoadSimulatedCapture(dir);
    std::vector<double> with_markers, with_cutout;
    int min_points = 1 << 30, failed = 0;
    for (const reconstruct::CapturePosition& p : capture.positions) {
      ++total;
      const PoseError m = Measure(p, capture.nominal, true);
      const PoseError c = Measure(p, capture.nominal, false);
      if (m.found) {
        with_markers.push_back(m.camera_mm);
        min_points = std::min(min_points, m.points);
      } else {
        ++marker_fallbacks;
      }
      if (c.found) {
        with_cutout.push_back(c.camera_mm);
      } else {
        ++failed;
      }
    }
    cutout_failures += failed;
    all_markers.insert(all_markers.end(), with_markers.begin(), with_markers.end());
    all_cutout.insert(all_cutout.end(), with_cutout.begin(), with_cutout.end());
    std::printf("| %s | %s / %s | %d | %s / %s | %d |\n", material.name.c_str(),
                Fixed(Percentile(with_markers, 0.5), 3).c_str(),
                Fixed(Percentile(with_markers, 1.0), 3).c_str(),
                with_markers.empty() ? 0 : min_points,
                Fixed(Percentile(with_cutout, 0.5), 3).c_str(),
                Fixed(Percentile(with_cutout, 1.0), 3).c_str(), failed);
    std::fflush(stdout);
    fs::remove_all(dir);
  }
  std::printf(
      "\nOver %d positions: markers median %s mm, 90th percentile %s, worst %s (%d fell "
      "back to the cut-out); cut-out median %s mm, 90th percentile %s, worst %s (%d "
      "without a pose). Wall %s s.\n",
      total, Fixed(Percentile(all_markers, 0.5), 3).c_str(),
      Fixed(Percentile(all_markers, 0.9), 3).c_str(),
      Fixed(Percentile(all_markers, 1.0), 3).c_str(), marker_fallbacks,
      Fixed(Percentile(all_cutout, 0.5), 3).c_str(), Fixed(Percentile(all_cutout, 0.9), 3).c_str(),
      Fixed(Percentile(all_cutout, 1.0), 3).c_str(), cutout_failures,
      Fixed(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0)
          .c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const bool more = i + 1 < argc;
    if (std::strcmp(argv[i], "--measured-dir") == 0 && more) {
      a.measured_dir = argv[++i];
    } else if (std::strcmp(argv[i], "--work") == 0 && more) {
      a.work = argv[++i];
    } else if (std::strcmp(argv[i], "--positions") == 0 && more) {
      a.positions = std::stoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--width") == 0 && more) {
      a.width = std::stoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--height") == 0 && more) {
      a.height = std::stoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--every") == 0 && more) {
      a.every = std::max(1, std::stoi(argv[++i]));
    } else {
      std::fprintf(stderr, "bench_marker_pose: unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  try {
    return Run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_marker_pose: %s\n", e.what());
    return 1;
  }
}
