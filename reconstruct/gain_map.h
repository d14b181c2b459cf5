// The flat field (`brdfrig rig calibrate flat`, rig.yaml `calibration: {flat: FILE}`) in the
// measurement: the camera's relative gain across the frame, vignetting and the light's fall-off
// across the target together, divided out of every merged photo before the paper calibrates
// the radiometry and the sample is read. The map is mean 1, so the paper's absolute level is
// unchanged on average; what it removes is the departure of each pixel from the centre's
// response, which the paper's own smooth field (radiometry.h) follows only to second order.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "reconstruct/hdr_merge.h"

namespace brdfrig::reconstruct {

// Reads the gain map (EXR, CV_32FC3: `rig calibrate flat` writes the one map in every channel;
// a map per channel is used as it is). Throws FileError naming the file: unreadable, a size
// other than the camera's (`intrinsics`), a gain not finite or outside [0.05, 20].
cv::Mat ReadGainMap(const std::filesystem::path& path, const geometry::Intrinsics& intrinsics);

// Divides the radiance by `gain` (ReadGainMap's, the image's size); nothing for an empty gain.
void ApplyGainMap(const cv::Mat& gain, HdrImage* hdr);

}  // namespace brdfrig::reconstruct
