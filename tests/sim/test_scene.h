// A small scene for fast tests: 320×240 camera straight above the target (at rest), focal
// 400 px, so pixel (u, v) sees world x = (u − 160)/400·0.5, y = −(v − 120)/400·0.5.
#pragma once

#include <string>

#include "sim/scene.h"

namespace brdfrig::sim::testing {

inline std::string BaseSceneYaml(
    const std::string& sample_brdf = "{model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}") {
  return R"(rig:
  camera: {resolution: [320, 240], focal_px: [400, 400], position: [0, 0, 0.5],
           look_at: [0, 0, 0], up: [0, 1, 0]}
  light: {position: [0.05, 0.1, 0.6], intensity: 2.0}
  axes:
    - {name: camera_arm, moves: camera, direction: [1, 0, 0], range_deg: [-80, 80]}
    - {name: light_arm, moves: light, direction: [1, 0, 0], range_deg: [-80, 80]}
  target: {cutout: [0.1, 0.08], paper: [0.3, 0.3], paper_albedo: 0.7}
sample:
  brdf: )" +
         sample_brdf + R"(
  size: [0.2, 0.2]
background: {albedo: 0.05}
sensor: {gain: 10, shutter_speeds: [0.001, 0.01, 0.1]}
render: {seed: 7}
timing:
  axes: {speed_deg_s: 20, acceleration_deg_s2: 40}
  shot_overhead_s: 0.25
  download_s: 1.5
  reopen_s: 2
)";
}

// The base scene plus extra top-level YAML (e.g. an `effects:` list).
inline Scene TestScene(
    const std::string& extra = "",
    const std::string& sample_brdf = "{model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}") {
  return LoadSceneString(BaseSceneYaml(sample_brdf) + extra, "scene.yaml");
}

}  // namespace brdfrig::sim::testing
