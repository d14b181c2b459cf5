#include "evaluate/display_image.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "common/error.h"
#include "common/srgb.h"
#include "sim/image_io.h"

namespace brdfrig::evaluate {

double AutoDisplayScale(const cv::Mat& radiance) {
  cv::Mat flat = radiance.reshape(1, 1).clone();
  std::vector<float> values(flat.begin<float>(), flat.end<float>());
  values.erase(std::remove_if(values.begin(), values.end(),
                              [](float v) { return !std::isfinite(v) || v <= 0; }),
               values.end());
  if (values.empty()) return 1.0;
  const auto k = static_cast<std::ptrdiff_t>(values.size() * 995 / 1000);
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return 1.0 / std::max(values[static_cast<std::size_t>(k)], 1e-30f);
}

cv::Mat ToDisplay8(const cv::Mat& radiance, double scale) {
  cv::Mat out(radiance.size(), CV_8UC3);
  for (int y = 0; y < radiance.rows; ++y) {
    const auto* in = radiance.ptr<cv::Vec3f>(y);
    auto* px = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < radiance.cols; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double v = std::isfinite(in[x][c]) ? scale * in[x][c] : 0.0;
        px[x][c] = static_cast<uchar>(std::lround(255 * SrgbEncode(v)));
      }
    }
  }
  return out;
}

cv::Mat DifferenceImage(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  return diff;
}

void WriteImageFile(const std::filesystem::path& path, const cv::Mat& radiance) {
  const std::string ext = path.extension().string();
  if (ext == ".exr") {
    sim::WriteRadianceExr(path, radiance);
    return;
  }
  if (ext != ".png" && ext != ".jpg") {
    throw Error("cannot write '" + path.string() + "': use .exr (radiance) or .png/.jpg (picture)");
  }
  if (!cv::imwrite(path.string(), ToDisplay8(radiance, AutoDisplayScale(radiance)))) {
    throw Error("cannot write '" + path.string() + "'");
  }
}

}  // namespace brdfrig::evaluate
