// The calibration files rig.yaml's `calibration:` references and a session's snapshot keeps
// (`brdfrig rig calibrate lens|white|light` write them): the same bytes through each JSON
// reader, so one corpus of valid files of every kind feeds all three.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "geometry/lens_calibration_file.h"
#include "geometry/light_calibration_file.h"
#include "geometry/white_reference_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = brdfrig::fuzz::WriteScratchFile("calibration.json", data, size);
  // Each throw is the documented rejection of a malformed calibration file.
  try {
    brdfrig::geometry::ReadLensCalibration(file);
  } catch (const brdfrig::Error&) {
  }
  try {
    brdfrig::geometry::ReadWhiteReference(file);
  } catch (const brdfrig::Error&) {
  }
  try {
    brdfrig::geometry::ReadLightCalibration(file);
  } catch (const brdfrig::Error&) {
  }
  return 0;
}
