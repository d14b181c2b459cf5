#include "reconstruct/gain_map.h"

#include <string>
#include <vector>

#include "common/error.h"
#include "common/exr_io.h"

namespace brdfrig::reconstruct {

cv::Mat ReadGainMap(const std::filesystem::path& path, const geometry::Intrinsics& intrinsics) {
  const cv::Mat image = ReadRadianceExr(path);  // FileError naming the file
  if (image.cols != intrinsics.width || image.rows != intrinsics.height) {
    throw FileError(path.string(),
                    "flat field of another camera: the map is " + std::to_string(image.cols) + "x" +
                        std::to_string(image.rows) + ", the camera's photos " +
                        std::to_string(intrinsics.width) + "x" + std::to_string(intrinsics.height));
  }
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  cv::Mat gain = channels[0];
  // NaN fails both comparisons, so it is caught with the out-of-range gains.
  const cv::Mat in_range = (gain >= 0.05) & (gain <= 20);
  if (cv::countNonZero(in_range) != static_cast<int>(gain.total())) {
    throw FileError(path.string(),
                    "flat field: gains must be finite and within [0.05, 20] (a map of relative "
                    "gain, mean 1, as `brdfrig rig calibrate flat` writes)");
  }
  return gain;
}

void ApplyGainMap(const cv::Mat& gain, HdrImage* hdr) {
  if (gain.empty()) return;
  cv::Mat gain3;
  cv::merge(std::vector<cv::Mat>{gain, gain, gain}, gain3);
  cv::divide(hdr->radiance, gain3, hdr->radiance);
}

}  // namespace brdfrig::reconstruct
