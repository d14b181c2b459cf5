#include "acquire/frame_check.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "common/photo_signature.h"

namespace brdfrig::acquire {
namespace {

bool Decodable(const std::string& file_name) {
  std::string ext = std::filesystem::path(file_name).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff";
}

}  // namespace

FrameCheck CheckFrame(std::span<const std::byte> bytes, const std::string& file_name,
                      const FrameCheckOptions& options, cv::Mat* levels) {
  FrameCheck check;
  if (bytes.empty()) {
    check.ok = false;
    check.problem = "empty file";
    return check;
  }
  if (!Decodable(file_name)) return check;  // RAW: LibRaw decoding belongs to reconstruct
  if (!HasPhotoSignature(bytes)) {
    check.ok = false;
    check.problem = "not a PNG, JPEG or TIFF image";
    return check;
  }
  const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8U,
                       const_cast<std::byte*>(bytes.data()));
  const cv::Mat image = cv::imdecode(buffer, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  if (image.empty()) {
    check.ok = false;
    check.problem = "does not decode as an image";
    return check;
  }
  check.decoded = true;
  check.width = image.cols;
  check.height = image.rows;
  if ((options.expected_width > 0 && image.cols != options.expected_width) ||
      (options.expected_height > 0 && image.rows != options.expected_height)) {
    check.ok = false;
    check.problem = "size " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                    ", expected " + std::to_string(options.expected_width) + "x" +
                    std::to_string(options.expected_height);
    return check;
  }
  double scale = 1.0;
  switch (image.depth()) {
    case CV_8U:
      scale = 1.0 / 255;
      break;
    case CV_16U:
      scale = 1.0 / 65535;
      break;
    default:
      scale = 1.0;
      break;  // float images are already in fractions of full scale
  }
  cv::Mat as_float;
  image.convertTo(as_float, CV_32F, scale);
  cv::Mat gray;
  if (as_float.channels() == 1) {
    gray = as_float;
  } else {
    std::vector<cv::Mat> channels;
    cv::split(as_float, channels);
    gray = channels[0].clone();
    for (std::size_t c = 1; c < channels.size(); ++c) gray = cv::max(gray, channels[c]);
  }
  double max_level = 0;
  cv::minMaxLoc(gray, nullptr, &max_level);
  check.max_level = max_level;
  check.saturated_fraction =
      static_cast<double>(cv::countNonZero(gray >= options.saturation_level)) /
      static_cast<double>(gray.total());
  if (max_level < options.black_level) {
    check.ok = false;
    check.problem =
        "all black (brightest pixel at " + std::to_string(max_level) + " of full scale)";
  }
  if (levels) *levels = gray;
  return check;
}

}  // namespace brdfrig::acquire
