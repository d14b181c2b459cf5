// Simulated captures with a known answer for the reconstruction tests: the default rig at a
// reduced resolution, a sample of our choosing, an ideal or a realistic sensor.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "brdf/material_file.h"
#include "reconstruct/capture_set.h"
#include "reconstruct/pipeline.h"
#include "sim/simulate.h"

namespace brdfrig::reconstruct::testing {

// A slice model that does not change with theta_in (one slice), so a per-position fit has one
// right answer whatever the incidence angle varies across the cut-out.
inline brdf::Material FlatSliceTruth() {
  brdf::Slice slice;
  slice.theta_in = 0.6;
  slice.channel[0] = {3.0, 0.05, 0.015, 0.060};  // R
  slice.channel[1] = {2.0, 0.04, 0.018, 0.050};  // G
  slice.channel[2] = {1.5, 0.02, 0.012, 0.070};  // B
  brdf::Material m;
  m.slices = {slice};
  return m;
}

// The largest relative error of the peak (a1) and tail (h) heights over every slice and
// channel of `fitted` against `truth`'s one slice (FlatSliceTruth).
inline double WorstSliceError(const brdf::Material& fitted, const brdf::Material& truth) {
  const brdf::Slice& want = truth.slices[0];
  double worst = 0;
  for (const brdf::Slice& slice : fitted.slices) {
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(slice.channel[c].a1 / want.channel[c].a1 - 1));
      worst = std::max(worst, std::abs(slice.channel[c].h / want.channel[c].h - 1));
    }
  }
  return worst;
}

// The seed rung alone (today's slice fit, no ladder): for tests of the measuring stages and of
// the slices themselves. With the light refinement: these tests' samples are slice models,
// lobes symmetric about the mirror direction, which is the refinement's premise
// (reconstruct/light_refine.h); it removes the highlight centroid's bias of tenths of a degree
// that would otherwise cost the slices' levels a few parts in a thousand.
inline ReconstructOptions SeedOnly() {
  ReconstructOptions options;
  options.model = "seed";
  options.light_refine.enabled = true;
  return options;
}

struct SceneSpec {
  std::string brdf = "{model: slices, file: truth.json}";
  std::string effects = "[]";
  std::string sensor_format = "png16";
  std::string positions =  // camera_arm, light_arm in degrees
      "[{camera_arm: 20, light_arm: -20}, {camera_arm: 40, light_arm: -40}, "
      "{camera_arm: 60, light_arm: -60}]";
  std::string exposures = "[0.001, 0.008, 0.0666667]";
  int width = 640, height = 480;
  // Edge pixels average n×n rays: the simulated edge is exact to about 1/(2n) px, which bounds
  // the corner accuracy a test can ask for.
  int supersampling = 16;
  std::string target = "{cutout: [0.1, 0.1], paper: [0.3, 0.3], paper_albedo: 0.8}";
  std::string extra;  // appended verbatim (e.g. faults)
};

inline std::string SceneYaml(const SceneSpec& s) {
  const double focal_mm = 50.0 * s.width / 1600.0 * 36 / 36;  // same field of view as default
  return "rig:\n"
         "  camera: {resolution: [" +
         std::to_string(s.width) + ", " + std::to_string(s.height) +
         "], focal_length_mm: " + std::to_string(focal_mm) +
         ", sensor_width_mm: " + std::to_string(36.0 * s.width / 1600.0) +
         ", position: [0, 0, 0.5], look_at: [0, 0, 0], up: [0, 1, 0]}\n"
         "  light: {position: [0, 0, 0.6], intensity: 1.0}\n"
         "  axes:\n"
         "    - {name: camera_arm, moves: camera, direction: [1, 0, 0], range_deg: [-85, 85]}\n"
         "    - {name: light_arm, moves: light, direction: [1, 0, 0], range_deg: [-85, 85]}\n"
         "    - {name: light_azimuth, moves: light, direction: [0, 0, 1], range_deg: [-180, 180]}\n"
         "  target: " +
         s.target +
         "\n"
         "sample:\n  brdf: " +
         s.brdf +
         "\n  size: [0.2, 0.2]\n"
         "background: {albedo: 0.05}\n"
         "sensor: {format: " +
         s.sensor_format +
         ", gain: 16}\n"
         "render: {supersampling: " +
         std::to_string(s.supersampling) +
         ", seed: 1}\n"
         "capture:\n  exposures: " +
         s.exposures + "\n  positions: " + s.positions +
         "\n"
         "effects: " +
         s.effects + "\n" + s.extra;
}

// Writes the scene (and the truth material when given) into `dir` and simulates the capture.
inline CaptureSet SimulateCapture(const std::filesystem::path& dir, const SceneSpec& spec,
                                  const brdf::Material* truth = nullptr) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  if (truth) brdf::WriteMaterialFile(dir / "truth.json", *truth);
  std::ofstream(dir / "scene.yaml") << SceneYaml(spec);
  sim::SimulateOptions options;
  options.scene = dir / "scene.yaml";
  options.output_dir = dir / "capture";
  options.write_truth = false;
  sim::Simulate(options);
  return LoadSimulatedCapture(dir / "capture");
}

}  // namespace brdfrig::reconstruct::testing
