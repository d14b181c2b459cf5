#include "evaluate/sample_figures.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.h"
#include "evaluate/sphere_test.h"

namespace brdfrig::evaluate {

SampleFigures CompareSampleRadiance(const cv::Mat& reference, const cv::Mat& fit,
                                    const cv::Mat& mask, const std::string& reference_name) {
  if (reference.size() != fit.size() || reference.type() != CV_32FC3 || fit.type() != CV_32FC3 ||
      mask.size() != reference.size() || mask.type() != CV_8UC1) {
    throw Error("sample figures: reference, fit and mask differ in size or type");
  }
  std::vector<float> values;
  for (int y = 0; y < reference.rows; ++y) {
    const float* p = reference.ptr<float>(y);
    const uchar* m = mask.ptr<uchar>(y);
    for (int x = 0; x < reference.cols; ++x) {
      if (m[x]) values.insert(values.end(), p + 3 * x, p + 3 * x + 3);
    }
  }
  if (values.empty()) throw Error("sample figures: no sample pixels (the cut-out is not in view)");
  const std::size_t rank = std::min(values.size() - 1, values.size() * 99 / 100);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank),
                   values.end());
  SampleFigures out;
  out.peak = values[rank];
  const double peak = out.peak > 0 ? out.peak : 1;  // black: the PSNR is set undefined below
  cv::Mat a(reference.size(), CV_32FC3), b(reference.size(), CV_32FC3);
  double se = 0, sq = 0;
  for (int y = 0; y < reference.rows; ++y) {
    const float* pt = reference.ptr<float>(y);
    const float* pf = fit.ptr<float>(y);
    const uchar* m = mask.ptr<uchar>(y);
    float* pa = a.ptr<float>(y);
    float* pb = b.ptr<float>(y);
    for (int i = 0; i < reference.cols * 3; ++i) {
      const double ft = std::isnan(pf[i]) ? 1e30 : pf[i];
      pa[i] = static_cast<float>(SrgbEncode(std::clamp(pt[i] / peak, 0.0, 1.0)));
      pb[i] = static_cast<float>(SrgbEncode(std::clamp(ft / peak, 0.0, 1.0)));
      if (m[i / 3]) {
        se += (ft - pt[i]) * (ft - pt[i]);
        sq += static_cast<double>(pt[i]) * pt[i];
      }
    }
  }
  out.normalized_sample = Psnr(a, b, mask, 1.0,
                               "sample only, linear radiance / " + reference_name +
                                   "'s 99th percentile in the view, clamped, sRGB");
  if (!(out.peak > 0)) out.normalized_sample.psnr_db = NAN;  // nothing to normalize by
  out.relative_rmse = sq > 0 ? std::sqrt(se / sq) : std::sqrt(se);
  out.relative_rmse_protocol = "sample only, linear radiance, RMS(fit - " + reference_name +
                               ") / RMS(" + reference_name + "), unclamped";
  return out;
}

DefinedMean MeanOfDefined(const std::vector<double>& values) {
  DefinedMean m;
  double sum = 0;
  for (const double v : values) {
    if (std::isnan(v)) continue;
    sum += v;
    ++m.count;
  }
  if (m.count > 0) m.mean = sum / m.count;
  return m;
}

}  // namespace brdfrig::evaluate
