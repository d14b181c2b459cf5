// Internal: the sensor pipeline behind Simulator::Expose.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "sim/scene.h"

namespace brdfrig::sim {

cv::Mat ApplySensor(const Scene& scene, const geometry::Intrinsics& intrinsics,
                    const cv::Mat& radiance, double exposure_s, std::uint64_t frame, int threads);

}  // namespace brdfrig::sim
