#include "evaluate/image_metrics.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"

namespace brdfrig::evaluate {

std::string PsnrResult::Report() const {
  std::ostringstream out;
  out.precision(3);
  out << std::fixed << psnr_db << " dB PSNR (" << protocol << "; peak " << peak << ", " << pixels
      << " px)";
  return out.str();
}

PsnrResult Psnr(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask, double peak,
                const std::string& protocol) {
  if (a.size() != b.size() || a.channels() != b.channels()) {
    throw Error("PSNR: images differ in size or channels");
  }
  if (!mask.empty() && (mask.size() != a.size() || mask.type() != CV_8UC1)) {
    throw Error("PSNR: mask must be 8-bit single channel of the image size");
  }
  if (!(peak > 0)) throw Error("PSNR: peak must be > 0");
  cv::Mat da, db;
  a.convertTo(da, CV_64F);
  b.convertTo(db, CV_64F);
  const int channels = a.channels();
  double sum = 0;
  long count = 0;
  for (int y = 0; y < a.rows; ++y) {
    const double* pa = da.ptr<double>(y);
    const double* pb = db.ptr<double>(y);
    const uchar* pm = mask.empty() ? nullptr : mask.ptr<uchar>(y);
    for (int x = 0; x < a.cols; ++x) {
      if (pm && !pm[x]) continue;
      for (int c = 0; c < channels; ++c) {
        const double d = pa[x * channels + c] - pb[x * channels + c];
        sum += d * d;
      }
      ++count;
    }
  }
  if (count == 0) throw Error("PSNR: the comparison region is empty");
  PsnrResult result;
  result.rmse = std::sqrt(sum / (static_cast<double>(count) * channels));
  result.peak = peak;
  result.pixels = count;
  result.protocol = protocol;
  result.psnr_db = result.rmse == 0 ? std::numeric_limits<double>::infinity()
                                    : 20 * std::log10(peak / result.rmse);
  return result;
}

}  // namespace brdfrig::evaluate
