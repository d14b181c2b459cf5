// Photos as the reconstruction reads them (reconstruct::ReadPhoto: PNG, TIFF, JPEG, ... through
// OpenCV's decoders, which go by content) and as the capture checks each downloaded frame
// (acquire::CheckFrame, from memory). EXR and RAW have their own targets.
#include <span>

#include "acquire/frame_check.h"
#include "common/error.h"
#include "fuzz/fuzz_input.h"
#include "reconstruct/hdr_merge.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    brdfrig::reconstruct::ReadPhoto(brdfrig::fuzz::WriteScratchFile("photo.png", data, size));
  } catch (const brdfrig::Error&) {
    // The documented rejection of an unreadable photo.
  }
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
  try {
    brdfrig::acquire::CheckFrame(bytes, "frame.png", {});
  } catch (const brdfrig::Error&) {
    // Same for a frame.
  }
  return 0;
}
