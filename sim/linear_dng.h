// A minimal linear DNG (uncompressed LinearRaw, 3 × 16 bits per pixel, sRGB primaries, neutral
// white balance, white level 65535) that LibRaw decodes back to the same linear values:
// the RAW half of the simulated camera's RAW+JPEG pairs, and RAW test data (no maker's file can
// be committed).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace brdfrig::sim {

// `bgr16` is CV_16UC3 in OpenCV's channel order; `model` goes into Model/UniqueCameraModel.
std::vector<std::uint8_t> EncodeLinearDng(const cv::Mat& bgr16, const std::string& model);

}  // namespace brdfrig::sim
