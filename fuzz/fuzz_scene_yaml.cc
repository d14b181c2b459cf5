// scene.yaml (the simulator's world: rig, sample, sensor, effects, faults). Relative file names
// in the scene resolve against the source tree, where the repository's scenes live.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "sim/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    brdfrig::sim::LoadSceneString(brdfrig::fuzz::AsString(data, size), "scene.yaml",
                                  BRDFRIG_SOURCE_DIR "/sim/scenes");
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed scene.
  }
  return 0;
}
