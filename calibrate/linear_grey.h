// A calibration photo's signal as one grey channel.
#pragma once

#include <opencv2/core.hpp>

namespace brdfrig::calibrate {

// The photo as CV_32F with full scale 1 (an integer photo's container full scale), its colour
// channels (not alpha) averaged with equal weights. Every calibration that reads grey takes a ratio
// within a photo or normalizes over it (the white tile against the paper, the flat field to mean
// 1), so a camera's per-channel gains cancel and any fixed weighting would do; equal weights keep a
// neutral target's value whatever the white balance.
cv::Mat LinearGrey(const cv::Mat& photo);

}  // namespace brdfrig::calibrate
