// OpenEXR photos and radiance images through the project's reader (common/exr_io.h), as
// reconstruct::ReadPhoto hands them over.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "reconstruct/hdr_merge.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    brdfrig::reconstruct::ReadPhoto(brdfrig::fuzz::WriteScratchFile("photo.exr", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of an unreadable photo.
  }
  return 0;
}
