// capture.json, the manifest of `brdfrig simulate` output that `reconstruct` reads
// (LoadSimulatedCapture). The directory also holds a valid scene and one photo, so that valid
// manifests reach the per-frame checks.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "reconstruct/capture_set.h"

namespace {

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
  static const bool setup = [] {
    brdfrig::fuzz::WriteScratchFile("scene.yaml", kScene);
    brdfrig::fuzz::WriteScratchFile("p00_e0.png", "not decoded by the loader");
    return true;
  }();
  (void)setup;
  try {
    brdfrig::fuzz::WriteScratchFile("capture.json", data, size);
    brdfrig::reconstruct::LoadSimulatedCapture(brdfrig::fuzz::ScratchDir());
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed manifest.
  }
  return 0;
}
