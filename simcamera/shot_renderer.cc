#include "simcamera/shot_renderer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "common/srgb.h"
#include "sim/linear_dng.h"
#include "simcamera/ptp_codes.h"

namespace brdfrig::simcamera {
namespace {

std::uint8_t SrgbCode(float linear) {
  return static_cast<std::uint8_t>(std::lround(SrgbEncode(linear) * 255));
}

CapturedFile Jpeg(const cv::Mat& sensor, int quality) {
  cv::Mat codes(sensor.size(), CV_8UC3);
  for (int y = 0; y < sensor.rows; ++y) {
    const float* in = sensor.ptr<float>(y);
    std::uint8_t* out = codes.ptr<std::uint8_t>(y);
    for (int i = 0; i < sensor.cols * 3; ++i) out[i] = SrgbCode(in[i]);
  }
  std::vector<std::uint8_t> buffer;
  if (!cv::imencode(".jpg", codes, buffer, {cv::IMWRITE_JPEG_QUALITY, quality})) {
    throw Error("the simulated camera could not encode a JPEG");
  }
  return {".JPG",
          format::kExifJpeg,
          std::move(buffer),
          static_cast<std::uint32_t>(sensor.cols),
          static_cast<std::uint32_t>(sensor.rows),
          24};
}

CapturedFile Dng(const cv::Mat& sensor, const std::string& model) {
  cv::Mat codes(sensor.size(), CV_16UC3);
  for (int y = 0; y < sensor.rows; ++y) {
    const float* in = sensor.ptr<float>(y);
    std::uint16_t* out = codes.ptr<std::uint16_t>(y);
    for (int i = 0; i < sensor.cols * 3; ++i) {
      out[i] = static_cast<std::uint16_t>(
          std::lround(std::clamp(static_cast<double>(in[i]), 0.0, 1.0) * 65535));
    }
  }
  return {".DNG",
          format::kDng,
          sim::EncodeLinearDng(codes, model),
          static_cast<std::uint32_t>(sensor.cols),
          static_cast<std::uint32_t>(sensor.rows),
          48};
}

}  // namespace

double EffectiveExposure(const ExposureSettings& exposure) {
  return exposure.exposure_s * (exposure.iso / 100.0) * std::pow(8.0 / exposure.f_number, 2);
}

ShotRenderer::ShotRenderer(sim::Scene scene, PositionsFunction positions, int threads)
    : simulator_(std::move(scene)), positions_(std::move(positions)), threads_(threads) {}

std::vector<CapturedFile> ShotRenderer::Shoot(const ExposureSettings& exposure) {
  last_positions_ = positions_ ? positions_() : geometry::AxisPositions{};
  if (!cached_pose_ || *cached_pose_ != last_positions_) {
    sim::RenderOptions options;
    options.threads = threads_;
    cached_radiance_ = simulator_.RenderRadiance(last_positions_, options);
    cached_pose_ = last_positions_;
  }
  ++shots_;
  const cv::Mat sensor = simulator_.Expose(cached_radiance_, EffectiveExposure(exposure),
                                           static_cast<std::uint64_t>(shots_), threads_);
  return {Jpeg(sensor, scene().sensor.jpeg_quality), Dng(sensor, scene().sensor.model)};
}

}  // namespace brdfrig::simcamera
