#include "brdf/metrics.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace brdfrig::brdf {
namespace {

const Vec3 kNormal = Vec3::UnitZ();

Vec3 Direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace

void MetricOptions::Validate() const {
  if (theta_steps < 2) throw OptionsError("MetricOptions.theta_steps must be >= 2");
  if (phi_steps < 2) throw OptionsError("MetricOptions.phi_steps must be >= 2");
}

double LogCosineError(const Brdf& a, const Brdf& b, const MetricOptions& options) {
  options.Validate();
  const int nt = options.theta_steps, np = options.phi_steps;
  const double dt = (M_PI / 2) / nt, dp = 2 * M_PI / np;
  double sum = 0, weight = 0;
  // Isotropic: the light azimuth can be fixed at 0.
  for (int i = 0; i < nt; ++i) {
    const double theta_i = (i + 0.5) * dt;
    const Vec3 l = Direction(theta_i, 0);
    const double cos_i = std::cos(theta_i);
    for (int j = 0; j < nt; ++j) {
      const double theta_o = (j + 0.5) * dt;
      const double w = std::sin(theta_i) * std::sin(theta_o);
      for (int k = 0; k < np; ++k) {
        const Vec3 v = Direction(theta_o, (k + 0.5) * dp);
        const Rgb fa = a.Eval(l, v, kNormal), fb = b.Eval(l, v, kNormal);
        const Rgb d = (1 + fa * cos_i).log() - (1 + fb * cos_i).log();
        sum += w * d.square().mean();
        weight += w;
      }
    }
  }
  return std::sqrt(sum / weight);
}

Rgb DirectionalAlbedo(const Brdf& brdf, double theta_in, const MetricOptions& options) {
  options.Validate();
  // With u = sin^2(theta_o), cos dω = ½ du dφ: the midpoint rule in u samples the cosine-weighted
  // hemisphere evenly.
  const Vec3 l = Direction(theta_in, 0);
  const int nu = 4 * options.theta_steps, np = options.phi_steps;
  Rgb sum = Rgb::Zero();
  for (int i = 0; i < nu; ++i) {
    const double u = (i + 0.5) / nu;
    const double theta_o = std::asin(std::sqrt(u));
    for (int k = 0; k < np; ++k) {
      sum += brdf.Eval(l, Direction(theta_o, (k + 0.5) * 2 * M_PI / np), kNormal);
    }
  }
  return sum * (0.5 * (1.0 / nu) * (2 * M_PI / np));
}

double ReciprocityError(const Brdf& brdf, const MetricOptions& options) {
  options.Validate();
  const int nt = options.theta_steps, np = options.phi_steps;
  double worst = 0;
  for (int i = 0; i < nt; ++i) {
    const Vec3 l = Direction((i + 0.5) * (M_PI / 2) / nt, 0.3);
    for (int j = 0; j < nt; ++j) {
      for (int k = 0; k < np; ++k) {
        const Vec3 v = Direction((j + 0.5) * (M_PI / 2) / nt, (k + 0.5) * 2 * M_PI / np);
        const Rgb f = brdf.Eval(l, v, kNormal), g = brdf.Eval(v, l, kNormal);
        const Rgb rel = (f - g).abs() / f.max(g).max(1e-12);
        worst = std::max(worst, rel.maxCoeff());
      }
    }
  }
  return worst;
}

}  // namespace brdfrig::brdf
