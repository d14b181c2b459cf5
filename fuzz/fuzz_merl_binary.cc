// MERL `.binary` tables. A valid table is 35 MB, so fuzzing explores the header and size
// checks (and the short reads) rather than the lookups.
#include "brdf/merl.h"
#include "common/error.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    brdfrig::brdf::MerlTable::Read(brdfrig::fuzz::WriteScratchFile("table.binary", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed table.
  }
  return 0;
}
