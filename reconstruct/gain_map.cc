#include "reconstruct/gain_map.h"

#include <opencv2/core.hpp>
#include <string>

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
  // NaN fails both comparisons, so it is caught with the out-of-range gains.
  cv::Mat in_range;
  cv::inRange(image, cv::Scalar::all(0.05), cv::Scalar::all(20), in_range);
  if (cv::countNonZero(in_range) != static_cast<int>(image.total())) {
    throw FileError(path.string(),
                    "flat field: gains must be finite and within [0.05, 20] (a map of relative "
                    "gain, mean 1, as `brdfrig rig calibrate flat` writes)");
  }
  return image;
}

void ApplyGainMap(const cv::Mat& gain, HdrImage* hdr) {
  if (!gain.empty()) cv::divide(hdr->radiance, gain, hdr->radiance);
}

}  // namespace brdfrig::reconstruct
