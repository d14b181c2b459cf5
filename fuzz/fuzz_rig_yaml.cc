// rig.yaml through the reader every tool uses (ReadRigDescription: geometry and the devices'
// shape). The file sits beside a valid scene.yaml so that `geometry: scene.yaml` resolves.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "rig/rig_file.h"

namespace {

// A scene whose `rig:` section a fuzzed rig.yaml may name as its geometry.
constexpr const char* kScene = R"(rig:
  camera: {resolution: [64, 48], focal_px: [80, 80], position: [0, 0, 0.5],
           look_at: [0, 0, 0], up: [0, 1, 0]}
  light: {position: [0, 0, 0.6], intensity: 2.0}
  axes:
    - {name: camera_arm, moves: camera, direction: [1, 0, 0], range_deg: [-80, 80]}
    - {name: light_arm, moves: light, direction: [1, 0, 0], range_deg: [-80, 80]}
  target: {cutout: [0.1, 0.08], paper: [0.3, 0.3], paper_albedo: 0.7}
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool scene_written = (brdfrig::fuzz::WriteScratchFile("scene.yaml", kScene), true);
  (void)scene_written;
  try {
    brdfrig::rig::ReadRigDescription(brdfrig::fuzz::WriteScratchFile("rig.yaml", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed rig file.
  }
  return 0;
}
