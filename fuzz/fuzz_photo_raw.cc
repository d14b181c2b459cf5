// Camera RAW photos through LibRaw (reconstruct/raw_photo.h), as reconstruct::ReadPhoto hands
// them over. The name says DNG; LibRaw identifies the format by content.
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "reconstruct/hdr_merge.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    brdfrig::reconstruct::ReadPhoto(brdfrig::fuzz::WriteScratchFile("photo.dng", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of an unreadable photo.
  }
  return 0;
}
