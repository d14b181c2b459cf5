#include "brdf/sphere_figure.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.h"
#include "common/parallel.h"
#include "common/srgb.h"

namespace brdfrig::brdf {
namespace {

// Linear radiance f · cos θi (R, G, B per pixel) and the sphere mask, as SphereRadiance lays
// them out (rows from the top, image up = +y, the light turned about the vertical axis).
void Radiance(const Brdf& brdf, double light_angle, int resolution, std::vector<float>* rgb,
              std::vector<char>* mask) {
  const Vec3 v(0, 0, 1);
  const Vec3 l(std::sin(light_angle), 0, std::cos(light_angle));
  const auto n_px = static_cast<std::size_t>(resolution) * resolution;
  rgb->assign(3 * n_px, 0.0f);
  mask->assign(n_px, 0);
  ParallelFor(static_cast<std::size_t>(resolution), [&](std::size_t begin, std::size_t end) {
    for (auto row = static_cast<int>(begin); row < static_cast<int>(end); ++row) {
      const double y = 1 - 2 * (row + 0.5) / resolution;
      for (int col = 0; col < resolution; ++col) {
        const double x = 2 * (col + 0.5) / resolution - 1;
        const double r2 = x * x + y * y;
        if (r2 >= 1) continue;
        const std::size_t i = static_cast<std::size_t>(row) * resolution + col;
        (*mask)[i] = 1;
        const Vec3 n(x, y, std::sqrt(1 - r2));
        const double cos_in = n.dot(l);
        if (cos_in <= 0) continue;
        const Rgb f = brdf.Eval(l, v, n) * cos_in;
        for (int c = 0; c < 3; ++c) (*rgb)[3 * i + c] = static_cast<float>(f[c]);
      }
    }
  });
}

double Percentile(const std::vector<float>& rgb, const std::vector<char>& mask, double fraction) {
  std::vector<float> values;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (mask[i]) values.insert(values.end(), rgb.begin() + 3 * i, rgb.begin() + 3 * i + 3);
  }
  if (values.empty()) return 0;
  const auto rank = static_cast<std::size_t>(
      std::clamp(std::ceil(fraction * static_cast<double>(values.size())) - 1, 0.0,
                 static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank),
                   values.end());
  return values[rank];
}

}  // namespace

void SphereFigureOptions::Validate() const {
  if (resolution < 8 || resolution > 4096) {
    throw OptionsError("SphereFigureOptions.resolution = " + std::to_string(resolution) +
                       "; must be in [8, 4096]");
  }
  if (light_angles_deg.empty()) throw OptionsError("SphereFigureOptions.light_angles_deg is empty");
  for (double a : light_angles_deg) {
    if (!(a >= 0 && a < 90)) {
      throw OptionsError("SphereFigureOptions.light_angles_deg: " + std::to_string(a) +
                         " must be in [0, 90)");
    }
  }
  if (!(percentile > 0 && percentile <= 1)) {
    throw OptionsError("SphereFigureOptions.percentile must be in (0, 1]");
  }
}

SphereFigure SpherePsnr(const Brdf& truth, const Brdf& fitted, const SphereFigureOptions& options) {
  options.Validate();
  SphereFigure out;
  out.worst_psnr_db = std::numeric_limits<double>::infinity();
  std::vector<float> t, f;
  std::vector<char> mask;
  for (double angle_deg : options.light_angles_deg) {
    const double angle = angle_deg * M_PI / 180;
    Radiance(truth, angle, options.resolution, &t, &mask);
    Radiance(fitted, angle, options.resolution, &f, &mask);
    double scale = Percentile(t, mask, options.percentile);
    if (!(scale > 0)) {
      const double max = t.empty() ? 0 : *std::max_element(t.begin(), t.end());
      scale = max > 0 ? max : 1;
    }
    double se = 0;
    long count = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
      if (!mask[i]) continue;
      ++count;
      for (int c = 0; c < 3; ++c) {
        const double a = t[3 * i + c], b = f[3 * i + c];
        const double db = std::isnan(b) ? 1.0 : std::clamp(b / scale, 0.0, 1.0);
        const double d = SrgbEncode(std::clamp(a / scale, 0.0, 1.0)) - SrgbEncode(db);
        se += d * d;
      }
    }
    const double mse = se / (3.0 * static_cast<double>(count));
    const double psnr = mse == 0 ? std::numeric_limits<double>::infinity() : -10 * std::log10(mse);
    out.psnr_db.push_back(psnr);
    out.mean_psnr_db += psnr / static_cast<double>(options.light_angles_deg.size());
    out.worst_psnr_db = std::min(out.worst_psnr_db, psnr);
  }
  return out;
}

}  // namespace brdfrig::brdf
