// Image comparison for evaluation. The seed compares a photo with a rendering of the fitted
// model by PSNR; we always say over which pixels and at which peak value it was computed.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace brdfrig::evaluate {

struct PsnrResult {
  double psnr_db = 0;    // +inf when the images are identical over the region
  double rmse = 0;       // in the images' units
  double peak = 0;       // the value PSNR is relative to
  long pixels = 0;       // pixels compared
  std::string protocol;  // e.g. "whole photo, 12-bit code values"
  std::string Report() const;
};

// PSNR = 20 log10(peak / RMSE) over the pixels where mask != 0 (all pixels for an empty mask),
// all channels. Images must have the same size and channel count (any depth; compared as
// double). Throws brdfrig::Error on mismatched inputs or an empty region.
PsnrResult Psnr(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask, double peak,
                const std::string& protocol);

}  // namespace brdfrig::evaluate
