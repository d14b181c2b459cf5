#include "evaluate/sphere_test.h"
#include "common/angles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/format.h"
#include "common/parallel.h"

namespace brdfrig::evaluate {
namespace {

// The value below which `fraction` of the sphere's channel values lie (nearest rank).
double Percentile(const cv::Mat& radiance, const cv::Mat& mask, double fraction) {
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(cv::countNonZero(mask)) * 3);
  for (int y = 0; y < radiance.rows; ++y) {
    const float* p = radiance.ptr<float>(y);
    const uchar* m = mask.ptr<uchar>(y);
    for (int x = 0; x < radiance.cols; ++x) {
      if (m[x]) values.insert(values.end(), p + 3 * x, p + 3 * x + 3);
    }
  }
  if (values.empty()) return 0;
  const auto rank = static_cast<std::size_t>(
      std::clamp(std::ceil(fraction * static_cast<double>(values.size())) - 1, 0.0,
                 static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank),
                   values.end());
  return values[rank];
}

cv::Mat Display(const cv::Mat& radiance, double scale) {
  cv::Mat out(radiance.size(), CV_8UC3);
  for (int y = 0; y < radiance.rows; ++y) {
    const float* p = radiance.ptr<float>(y);
    uchar* o = out.ptr<uchar>(y);
    for (int i = 0; i < radiance.cols * 3; ++i) {
      const double v = std::isnan(p[i]) ? 1.0 : std::clamp(p[i] / scale, 0.0, 1.0);
      o[i] = static_cast<uchar>(std::lround(255 * SrgbEncode(v)));
    }
  }
  return out;
}

}  // namespace

void SphereTestOptions::Validate() const {
  if (resolution < 8 || resolution > 4096) {
    throw OptionsError("sphere test: resolution = " + std::to_string(resolution) +
                       " must be in [8, 4096] pixels");
  }
  if (light_angles_deg.empty()) throw OptionsError("sphere test: light_angles_deg is empty");
  for (double a : light_angles_deg) {
    if (!(a >= 0 && a < 90)) {
      throw OptionsError("sphere test: light angle " + Fixed(a, 3) +
                         " deg must be in [0, 90) (a light behind the sphere lights nothing)");
    }
  }
  if (!(percentile > 0 && percentile <= 1)) {
    throw OptionsError("sphere test: percentile = " + Fixed(percentile, 4) + " must be in (0, 1]");
  }
}

std::string SphereTestResult::Report() const {
  std::ostringstream out;
  out << "sphere test: mean " << Fixed(mean_psnr_db, 2) << " dB (worst " << Fixed(worst_psnr_db, 2)
      << " dB), relative RMSE " << Fixed(mean_relative_rmse, 4) << " [";
  for (std::size_t i = 0; i < lights.size(); ++i) {
    out << (i ? ", " : "") << Fixed(lights[i].light_angle_deg, 0)
        << "°: " << Fixed(lights[i].psnr_db, 2) << " dB";
  }
  out << "] (" << protocol << ")";
  return out.str();
}

cv::Mat SphereRadiance(const brdf::Brdf& brdf, double light_angle, int resolution, cv::Mat* mask) {
  // Orthographic camera looking down −z; the light turned from the view direction about the
  // image's vertical axis (the material is isotropic, so which axis does not matter).
  const brdf::Vec3 v(0, 0, 1);
  const brdf::Vec3 l(std::sin(light_angle), 0, std::cos(light_angle));
  cv::Mat radiance(resolution, resolution, CV_32FC3, cv::Scalar::all(0));
  cv::Mat sphere(resolution, resolution, CV_8UC1, cv::Scalar(0));
  ParallelFor(static_cast<std::size_t>(resolution), [&](std::size_t begin, std::size_t end) {
    for (auto row = static_cast<int>(begin); row < static_cast<int>(end); ++row) {
      float* out = radiance.ptr<float>(row);
      uchar* m = sphere.ptr<uchar>(row);
      const double y = 1 - 2 * (row + 0.5) / resolution;  // image up = +y
      for (int col = 0; col < resolution; ++col) {
        const double x = 2 * (col + 0.5) / resolution - 1;
        const double r2 = x * x + y * y;
        if (r2 >= 1) continue;
        m[col] = 255;
        const brdf::Vec3 n(x, y, std::sqrt(1 - r2));
        const double cos_in = n.dot(l);
        if (cos_in <= 0) continue;
        const brdf::Rgb f = brdf.Eval(l, v, n) * cos_in;
        for (int c = 0; c < 3; ++c) out[3 * col + c] = static_cast<float>(f[2 - c]);
      }
    }
  });
  if (mask) *mask = sphere;
  return radiance;
}

SphereTestResult SphereTest(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                            const SphereTestOptions& options) {
  options.Validate();
  SphereTestResult result;
  result.protocol = "orthographic sphere " + std::to_string(options.resolution) + " px, " +
                    "directional light, linear f·cos θi scaled so the truth's " +
                    Fixed(options.percentile * 100, 0) +
                    "th percentile over sphere pixels is 1, clamped, sRGB, PSNR over sphere "
                    "pixels; relative RMSE in linear radiance, unclamped";
  result.worst_psnr_db = std::numeric_limits<double>::infinity();
  for (double angle_deg : options.light_angles_deg) {
    cv::Mat mask;
    const cv::Mat t = SphereRadiance(truth, Radians(angle_deg), options.resolution, &mask);
    const cv::Mat f = SphereRadiance(fitted, Radians(angle_deg), options.resolution);
    SphereLight light;
    light.light_angle_deg = angle_deg;
    light.scale = Percentile(t, mask, options.percentile);
    // A black truth has no scale of its own; its brightest value (or 1) keeps the figures
    // defined instead of dividing by zero.
    if (!(light.scale > 0)) {
      double max = 0;
      cv::minMaxLoc(t.reshape(1), nullptr, &max);
      light.scale = max > 0 ? max : 1;
    }
    double se_display = 0, se_linear = 0, truth_sq = 0;
    long count = 0;
    for (int y = 0; y < t.rows; ++y) {
      const float* pt = t.ptr<float>(y);
      const float* pf = f.ptr<float>(y);
      const uchar* m = mask.ptr<uchar>(y);
      for (int x = 0; x < t.cols; ++x) {
        if (!m[x]) continue;
        ++count;
        for (int c = 0; c < 3; ++c) {
          const double a = pt[3 * x + c], b = pf[3 * x + c];
          // A NaN from the fit is as wrong as it gets: full white in display, infinite error.
          const double db = std::isnan(b) ? 1.0 : std::clamp(b / light.scale, 0.0, 1.0);
          const double d = SrgbEncode(std::clamp(a / light.scale, 0.0, 1.0)) - SrgbEncode(db);
          se_display += d * d;
          se_linear +=
              std::isfinite(b) ? (b - a) * (b - a) : std::numeric_limits<double>::infinity();
          truth_sq += a * a;
        }
      }
    }
    light.pixels = count;
    const double mse = se_display / (3.0 * static_cast<double>(count));
    light.psnr_db = mse == 0 ? std::numeric_limits<double>::infinity() : -10 * std::log10(mse);
    light.relative_rmse = truth_sq > 0    ? std::sqrt(se_linear / truth_sq)
                          : se_linear > 0 ? std::numeric_limits<double>::infinity()
                                          : 0;
    if (options.keep_images) {
      light.truth_image = Display(t, light.scale);
      light.fitted_image = Display(f, light.scale);
    }
    result.mean_psnr_db += light.psnr_db / static_cast<double>(options.light_angles_deg.size());
    result.mean_relative_rmse +=
        light.relative_rmse / static_cast<double>(options.light_angles_deg.size());
    result.worst_psnr_db = std::min(result.worst_psnr_db, light.psnr_db);
    result.lights.push_back(std::move(light));
  }
  return result;
}

}  // namespace brdfrig::evaluate
