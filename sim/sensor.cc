#include "sim/sensor.h"

#include <algorithm>
#include <cmath>

#include "common/parallel.h"
#include "sim/pixel_rng.h"

namespace brdfrig::sim {
namespace {

// Stream ids: each noise effect draws from its own stream.
constexpr std::uint64_t kShotNoiseStream = 1;
constexpr std::uint64_t kReadNoiseStream = 2;

double VignettingFactor(const VignettingEffect& v, const geometry::Intrinsics& k, int x, int y) {
  const double dx = x - k.cx, dy = y - k.cy;
  if (v.falloff == VignettingEffect::Falloff::kCos4) {
    // cos of the angle between the pixel's ray and the optical axis, to the fourth.
    const double t2 = (dx / k.fx) * (dx / k.fx) + (dy / k.fy) * (dy / k.fy);
    return 1.0 / ((1.0 + t2) * (1.0 + t2));
  }
  const double half_diagonal2 =
      0.25 * (static_cast<double>(k.width) * k.width + static_cast<double>(k.height) * k.height);
  const double r2 = (dx * dx + dy * dy) / half_diagonal2;
  return 1.0 + v.a1 * r2 + v.a2 * r2 * r2;
}

}  // namespace

cv::Mat ApplySensor(const Scene& scene, const geometry::Intrinsics& k, const cv::Mat& radiance,
                    double exposure_s, std::uint64_t frame, int threads) {
  CV_Assert(radiance.type() == CV_32FC3);
  const Effects& fx = scene.effects;
  const double scale = exposure_s * scene.sensor.gain;
  const std::uint64_t seed = scene.render.seed;
  const double adc_levels = fx.quantization ? std::ldexp(1.0, fx.quantization->bits) - 1 : 0;
  cv::Mat out(radiance.size(), CV_32FC3);
  ParallelFor(
      radiance.rows,
      [&](std::size_t begin, std::size_t end) {
        for (int y = static_cast<int>(begin); y < static_cast<int>(end); ++y) {
          const auto* in = radiance.ptr<cv::Vec3f>(y);
          auto* dst = out.ptr<cv::Vec3f>(y);
          for (int x = 0; x < radiance.cols; ++x) {
            double pixel_scale = scale;
            if (fx.vignetting) pixel_scale *= VignettingFactor(*fx.vignetting, k, x, y);
            const std::uint64_t index = static_cast<std::uint64_t>(y) * radiance.cols + x;
            for (int c = 0; c < 3; ++c) {
              double v = in[x][c] * pixel_scale;
              if (fx.shot_noise) {
                PixelRng rng(seed, frame, kShotNoiseStream * 4 + c, index);
                const double well = fx.shot_noise->full_well;
                v = rng.Poisson(std::max(v, 0.0) * well) / well;
              }
              if (fx.read_noise) {
                PixelRng rng(seed, frame, kReadNoiseStream * 4 + c, index);
                v += fx.read_noise->sigma * rng.Gaussian();
              }
              if (fx.saturation) v = std::min(v, fx.saturation->level);
              if (fx.quantization)
                v = std::round(std::clamp(v, 0.0, 1.0) * adc_levels) / adc_levels;
              if (fx.response_curve) v = fx.response_curve->Apply(v);
              dst[x][c] = static_cast<float>(v);
            }
          }
        }
      },
      threads);
  return out;
}

}  // namespace brdfrig::sim
