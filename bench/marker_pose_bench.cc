// The pose from the marker mask against the pose from the cut-out's corners, on the measured
// materials (issue 24 item 3). For each material: the default scene (its noise, its sensor)
// captured at every position of the designed plan twice, on the plain mask and on the marker
// mask. Each position's camera centre against the simulator's truth: from the markers (marker
// mask), from the cut-out's corners (plain mask: the pose before the markers), and from the
// cut-out's corners on the marker mask (the fallback when too few markers are found). Prints a
// per-material table and the distribution over all positions.
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

// One position measured with the rig as given; `cutout_only` forces the cut-out's corners
// (a marker mask's fallback).
PoseError Measure(const reconstruct::CapturePosition& position, const geometry::RigGeometry& rig,
                  bool cutout_only) {
  reconstruct::MeasureOptions options;
  if (cutout_only) options.target.min_markers = 1 << 20;
  PoseError e;
  try {
    reconstruct::MeasureState state;
    const reconstruct::MeasuredPosition m =
        reconstruct::MeasurePosition(position, rig, options, &state);
    e.found = m.report.pose_from == (rig.target.markers && !cutout_only ? "markers" : "cut-out");
    e.camera_mm = 1e3 * m.report.camera_disagreement_m;
    e.rms_px = m.report.reprojection_rms_px;
    e.points = m.report.pose_points;
  } catch (const std::exception& ex) {
    e.error = ex.what();
  }
  return e;
}

// The capture of `scene` at the plan's positions, as the reconstruction reads it (the rig as
// the scene has it: the lab's rig file is right about the mask it printed).
reconstruct::CaptureSet Capture(const std::shared_ptr<sim::Scene>& scene,
                                const jobs::StudyPlan& plan, const fs::path& dir) {
  fs::remove_all(dir);
  sim::SimulateOptions options;
  options.scene = fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml";
  options.loaded_scene = scene;
  options.output_dir = dir;
  options.positions = plan.positions;
  options.write_truth = false;
  sim::Simulate(options);
  reconstruct::CaptureSet capture = reconstruct::LoadSimulatedCapture(dir);
  capture.nominal.target = scene->rig.target;
  return capture;
}

// Camera-centre errors (mm) of the positions measured; failures counted.
struct Column {
  std::vector<double> mm;
  int failed = 0;
  int min_points = 1 << 30;
  void Add(const PoseError& e) {
    if (!e.found) {
      ++failed;
      return;
    }
    mm.push_back(e.camera_mm);
    min_points = std::min(min_points, e.points);
  }
  void Append(const Column& other) {
    mm.insert(mm.end(), other.mm.begin(), other.mm.end());
    failed += other.failed;
  }
};

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5))];
}

std::string Cell(const Column& c) {
  std::string text = Fixed(Percentile(c.mm, 0.5), 3) + " / " + Fixed(Percentile(c.mm, 1.0), 3);
  if (c.failed > 0) text += " (" + std::to_string(c.failed) + " failed)";
  return text;
}

int Run(const Args& a) {
  std::vector<jobs::StudyMaterial> materials = jobs::MeasuredStudyMaterials(a.measured_dir);
  std::vector<jobs::StudyMaterial> chosen;
  for (std::size_t i = 0; i < materials.size(); i += a.every) chosen.push_back(materials[i]);
  if (chosen.empty()) throw Error("no measured materials in " + a.measured_dir.string());
  const jobs::StudyPlan plan = jobs::DesignedPlan(a.positions);
  std::printf(
      "Pose from the marker mask vs the cut-out: %zu materials, %s, %d×%d, the default "
      "scene's noise; camera-centre error against the simulator's truth (mm)\n\n",
      chosen.size(), plan.name.c_str(), a.width, a.height);
  std::printf(
      "| material | marker mask, markers: median / worst mm (fewest corners) | plain mask, "
      "cut-out: median / worst mm | marker mask, cut-out only: median / worst mm |\n"
      "| --- | ---: | ---: | ---: |\n");
  Column all_markers, all_plain, all_fallback;
  const auto start = std::chrono::steady_clock::now();
  for (const jobs::StudyMaterial& material : chosen) {
    jobs::StudySettings s;
    s.width = a.width;
    s.height = a.height;
    s.sample_brdf = material.brdf_yaml;
    auto plain = std::make_shared<sim::Scene>(
        jobs::StudyScene(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml", s));
    auto marked = std::make_shared<sim::Scene>(*plain);
    marked->rig.target.markers = geometry::MaskMarkerRing{};
    const reconstruct::CaptureSet plain_capture = Capture(plain, plan, a.work / "plain");
    const reconstruct::CaptureSet marked_capture = Capture(marked, plan, a.work / "marked");
    Column markers, cutout, fallback;
    for (std::size_t i = 0; i < plain_capture.positions.size(); ++i) {
      cutout.Add(Measure(plain_capture.positions[i], plain_capture.nominal, false));
      markers.Add(Measure(marked_capture.positions[i], marked_capture.nominal, false));
      fallback.Add(Measure(marked_capture.positions[i], marked_capture.nominal, true));
    }
    std::printf("| %s | %s (%d) | %s | %s |\n", material.name.c_str(), Cell(markers).c_str(),
                markers.mm.empty() ? 0 : markers.min_points, Cell(cutout).c_str(),
                Cell(fallback).c_str());
    std::fflush(stdout);
    all_markers.Append(markers);
    all_plain.Append(cutout);
    all_fallback.Append(fallback);
  }
  fs::remove_all(a.work);
  std::printf(
      "\n| over all positions | median mm | 90th percentile | worst | failed |\n"
      "| --- | ---: | ---: | ---: | ---: |\n");
  const std::pair<const char*, const Column*> rows[] = {
      {"marker mask, markers", &all_markers},
      {"plain mask, cut-out", &all_plain},
      {"marker mask, cut-out only", &all_fallback}};
  for (const auto& [name, c] : rows) {
    std::printf("| %s | %s | %s | %s | %d of %zu |\n", name,
                Fixed(Percentile(c->mm, 0.5), 3).c_str(), Fixed(Percentile(c->mm, 0.9), 3).c_str(),
                Fixed(Percentile(c->mm, 1.0), 3).c_str(), c->failed, c->mm.size() + c->failed);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\nWall %s s.\n", Fixed(wall, 0).c_str());
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
