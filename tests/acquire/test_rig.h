// A small simulated rig for the acquisition tests: 64×48 pixels, no noise (so a session is
// deterministic and byte-identical whatever its interruptions), plus helpers to write
// rig.yaml, scene.yaml and plan.yaml into a fresh directory.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "sim/devices.h"

namespace brdfrig::acquire::testing {

namespace fs = std::filesystem;

inline std::string SmallSceneYaml(const std::string& extra = "") {
  return R"(rig:
  camera: {resolution: [64, 48], focal_px: [80, 80], position: [0, 0, 0.5],
           look_at: [0, 0, 0], up: [0, 1, 0]}
  light: {position: [0, 0, 0.6], intensity: 2.0}
  axes:
    - {name: camera_arm, moves: camera, direction: [1, 0, 0], range_deg: [-80, 80]}
    - {name: light_arm, moves: light, direction: [1, 0, 0], range_deg: [-80, 80]}
  target: {cutout: [0.1, 0.08], paper: [0.3, 0.3], paper_albedo: 0.7}
sample:
  brdf: {model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}
  size: [0.2, 0.2]
background: {albedo: 0.05}
sensor: {gain: 10, shutter_speeds: [0.001, 0.01, 0.1]}
render: {seed: 7}
timing:
  axes: {speed_deg_s: 20, acceleration_deg_s2: 40}
  shot_overhead_s: 0.25
  download_s: 1.5
  reopen_s: 2
)" + extra;
}

inline std::string RigYaml() {
  return R"(geometry: scene.yaml
camera: {backend: sim, scene: scene.yaml}
axes:
  camera_arm: {backend: sim, scene: scene.yaml}
  light_arm: {backend: sim, scene: scene.yaml}
light: {backend: sim, scene: scene.yaml}
)";
}

inline std::string SmallPlanYaml() {
  return R"(sample: test-sample
operator: tester
notes: acquisition test
positions:
  - {camera_arm: 20, light_arm: -20}
  - {camera_arm: 35, light_arm: -35}
  - {camera_arm: 50, light_arm: -50}
exposures: [0.001, 0.01]
settle_s: 0
)";
}

struct TestRig {
  fs::path dir;
  fs::path rig_file;
  fs::path plan_file;
  fs::path sessions;  // where tests put their sessions
};

// A fresh directory under the temp dir with scene.yaml, rig.yaml and plan.yaml.
inline TestRig MakeTestRig(const std::string& name, const std::string& scene_extra = "",
                           const std::string& plan = SmallPlanYaml()) {
  TestRig rig;
  rig.dir = fs::temp_directory_path() / ("brdfrig_acquire_" + name);
  fs::remove_all(rig.dir);
  fs::create_directories(rig.dir / "sessions");
  std::ofstream(rig.dir / "scene.yaml") << SmallSceneYaml(scene_extra);
  std::ofstream(rig.dir / "rig.yaml") << RigYaml();
  std::ofstream(rig.dir / "plan.yaml") << plan;
  rig.rig_file = rig.dir / "rig.yaml";
  rig.plan_file = rig.dir / "plan.yaml";
  rig.sessions = rig.dir / "sessions";
  sim::RegisterSimBackends();
  return rig;
}

}  // namespace brdfrig::acquire::testing
