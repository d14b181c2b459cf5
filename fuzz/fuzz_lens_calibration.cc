// The lens calibration file (`brdfrig rig calibrate lens` writes it, rig.yaml's
// `calibration: {lens: FILE}` and a session's snapshot read it) through its one reader.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "geometry/lens_calibration_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    brdfrig::geometry::ReadLensCalibration(
        brdfrig::fuzz::WriteScratchFile("lens.json", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed calibration file.
  }
  return 0;
}
