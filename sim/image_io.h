// Files the simulator writes: photos as a camera would (via OpenCV imgcodecs), and, for
// evaluation only, the true radiance (OpenEXR, 32-bit float R, G, B) and true geometry (JSON).
#pragma once

#include <cstddef>
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

#include "common/exr_io.h"
#include "sim/scene.h"

namespace brdfrig::sim {

struct TrueGeometry;

// Sensor image (CV_32FC3, B,G,R, 1 = full scale) → file bytes: clamped to [0, 1] and rounded
// to 65535 (PNG16, TIFF16) or 255 levels (JPEG8 at sensor.jpeg_quality).
std::vector<std::byte> EncodePhoto(const cv::Mat& sensor_image, const SensorDescription& sensor);

// The true radiance is written with common/exr_io.h.
using brdfrig::ReadRadianceExr;
using brdfrig::WriteRadianceExr;

void WriteTrueGeometry(const std::filesystem::path& path, const TrueGeometry& geometry);

}  // namespace brdfrig::sim
