// The exposure-independent figures of a view's sample pixels, shared by the held-out views (the
// simulator's radiance of the truth against a rendering of the fit) and the validation photos
// of a capture (a photo's HDR radiance against the fit's prediction under the measured
// geometry), so both name and compute the same protocol:
//   normalized sample PSNR — both divided by the reference's 99th percentile over the sample
//                  pixels (channels pooled), clamped to [0, 1], sRGB-encoded, peak 1;
//   relative RMSE — sqrt(mean (fit − reference)²) / sqrt(mean reference²) over the sample
//                  pixels, linear and unclamped.
// Where the reference is black over the sample (its 99th percentile is 0: a mirror seen away
// from its highlight) there is nothing to normalize by, and the normalized PSNR is NaN
// (undefined) rather than a figure on an arbitrary scale: means over views leave such views
// out (MeanOfDefined) and say how many they kept. The absolute figures still judge the view.
#pragma once

#include <cmath>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "evaluate/image_metrics.h"

namespace brdfrig::evaluate {

struct SampleFigures {
  PsnrResult normalized_sample;
  double relative_rmse = 0;
  std::string relative_rmse_protocol;
  double peak = 0;  // the reference's 99th percentile over the sample pixels
};

// `reference` and `fit`: linear radiance (CV_32FC3, same size; NaN in `fit` counts as a huge
// error); `mask`: CV_8U, the sample pixels. `reference_name` names the reference in the
// protocols ("truth", "photo"). Throws brdfrig::Error when the mask is empty.
SampleFigures CompareSampleRadiance(const cv::Mat& reference, const cv::Mat& fit,
                                    const cv::Mat& mask, const std::string& reference_name);

// Mean and count of the values that are not NaN (NaN and 0 when there are none).
struct DefinedMean {
  double mean = NAN;
  int count = 0;
};
DefinedMean MeanOfDefined(const std::vector<double>& values);

}  // namespace brdfrig::evaluate
