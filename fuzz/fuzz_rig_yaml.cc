// rig.yaml through the reader every tool uses (ReadRigDescription: geometry and the devices'
// shape). The file sits beside a valid scene.yaml so that `geometry: scene.yaml` resolves.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "rig/rig_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool scene_written =
      (brdfrig::fuzz::WriteScratchFile("scene.yaml", brdfrig::fuzz::kSmallScene), true);
  (void)scene_written;
  try {
    brdfrig::rig::ReadRigDescription(brdfrig::fuzz::WriteScratchFile("rig.yaml", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed rig file.
  }
  return 0;
}
