// capture.json, the manifest of `brdfrig simulate` output that `reconstruct` reads
// (LoadSimulatedCapture). The directory also holds a valid scene and one photo, so that valid
// manifests reach the per-frame checks.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "reconstruct/capture_set.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool setup = [] {
    brdfrig::fuzz::WriteScratchFile("scene.yaml", brdfrig::fuzz::kSmallScene);
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
