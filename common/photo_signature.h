// Which bytes may go to OpenCV's image decoders. OpenCV picks a decoder by content, not by name,
// and hands signatures it knows to decoders of its own, GDCM's DICOM reader among them, which
// aborts the process on a malformed file (fuzz_photo found one). The project's photos are PNG,
// JPEG or TIFF (EXR and camera RAW have readers of their own), so only those signatures pass.
#pragma once

#include <cstddef>
#include <span>

namespace brdfrig {

bool HasPhotoSignature(std::span<const std::byte> head);  // the file's first bytes (>= 8 read)

}  // namespace brdfrig
