// `brdfrig simulate`: a bracketed capture of a scene by the simulated rig, written the way the
// photos would arrive from a camera, with the truth kept apart:
//
//   DIR/photos/p00_e0.png ...   the photos (sensor.format)
//   DIR/photos/capture.json     what the rig reported: axis readings, exposures, durations
//   DIR/truth/p00.exr           true radiance per position (float, for evaluation only)
//   DIR/truth/p00.json          true geometry per position (camera pose, light, intrinsics)
//
// A scene holding a printed board (`board:`) is photographed once per board pose instead:
// DIR/photos/board_00.png ..., DIR/truth/board_00.json (with the page's pose).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::sim {

struct Scene;

struct SimulateOptions {
  std::filesystem::path scene;
  // When set, this scene (e.g. a loaded scene with edits) is simulated instead of reading
  // `scene` again; `scene` still names the file recorded in capture.json.
  std::shared_ptr<const Scene> loaded_scene;
  std::filesystem::path output_dir;
  std::vector<geometry::AxisPositions> positions;  // radians; empty: the scene's capture.positions
  std::vector<double> exposures;                   // seconds; empty: the scene's capture.exposures
  int threads = 0;                                 // 0 = all hardware threads
  bool write_truth = true;
  void Validate() const;  // throws OptionsError
};

struct SimulateSummary {
  int positions = 0;
  int frames = 0;
  int recovered_faults = 0;   // busy/disconnect/alarm answers the run recovered from
  double virtual_time_s = 0;  // capture time the rig would have taken
  double wall_time_s = 0;
  std::filesystem::path photos_dir, truth_dir;
  // Exposures the camera took more than a third of a stop away from the one asked for (a
  // camera offers its own shutter speeds within its own range; capture.json records what it
  // took), once per requested exposure.
  std::vector<std::string> warnings;
  std::string ToString() const;
};

SimulateSummary Simulate(const SimulateOptions& options);

}  // namespace brdfrig::sim
