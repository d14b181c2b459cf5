#include "sim/image_io.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "common/atomic_file.h"
#include "sim/simulator.h"

namespace brdfrig::sim {

std::vector<std::byte> EncodePhoto(const cv::Mat& sensor_image, const SensorDescription& sensor) {
  CV_Assert(sensor_image.type() == CV_32FC3);
  const bool eight_bit = sensor.format == PhotoFormat::kJpeg8;
  const double levels = eight_bit ? 255.0 : 65535.0;
  cv::Mat codes(sensor_image.size(), eight_bit ? CV_8UC3 : CV_16UC3);
  for (int y = 0; y < sensor_image.rows; ++y) {
    const float* in = sensor_image.ptr<float>(y);
    for (int i = 0; i < sensor_image.cols * 3; ++i) {
      const double code = std::round(std::clamp(static_cast<double>(in[i]), 0.0, 1.0) * levels);
      if (eight_bit) {
        codes.ptr<std::uint8_t>(y)[i] = static_cast<std::uint8_t>(code);
      } else {
        codes.ptr<std::uint16_t>(y)[i] = static_cast<std::uint16_t>(code);
      }
    }
  }
  std::vector<int> params;
  if (eight_bit) params = {cv::IMWRITE_JPEG_QUALITY, sensor.jpeg_quality};
  if (sensor.format == PhotoFormat::kPng16) params = {cv::IMWRITE_PNG_COMPRESSION, 1};
  std::vector<std::uint8_t> buffer;
  if (!cv::imencode(sensor.Extension(), codes, buffer, params)) {
    throw Error("could not encode a " + sensor.Extension() + " image");
  }
  std::vector<std::byte> bytes(buffer.size());
  std::transform(buffer.begin(), buffer.end(), bytes.begin(),
                 [](std::uint8_t b) { return static_cast<std::byte>(b); });
  return bytes;
}

void WriteTrueGeometry(const std::filesystem::path& path, const TrueGeometry& geometry) {
  WriteFileAtomically(path, geometry.ToJson().dump(2) + "\n");
}

}  // namespace brdfrig::sim
