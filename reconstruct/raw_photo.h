// Camera RAW files (NEF, CR2, CR3, ARW, DNG, ...) decoded through LibRaw into linear 16-bit BGR:
// no gamma, no automatic brightening, the camera's white balance, no rotation — so the values
// stay proportional to exposure × radiance and the pixel grid matches the camera intrinsics.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>

namespace brdfrig::reconstruct {

// Whether the file's extension names a RAW format (case-insensitive).
bool IsRawPhoto(const std::filesystem::path& path);

// CV_16UC3, B,G,R, full scale = the sensor's white level. Throws FileError naming the file and
// LibRaw's reason when it cannot be decoded.
cv::Mat ReadRawPhoto(const std::filesystem::path& path);

}  // namespace brdfrig::reconstruct
