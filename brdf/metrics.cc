#include "brdf/metrics.h"

#include <algorithm>
#include <cmath>

#include "brdf/quadrature.h"
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
  // A sharp lobe is a tiny spot about the mirror direction r: a grid uniform over the hemisphere
  // misses or over-weights it by up to 20 %. So v is written in polar coordinates about r,
  // v = cos(a) r + sin(a) (cos(b) e1 + sin(b) e2), dω = sin(a) da db, with
  //  - while the whole circle of radius a stays above the horizon (a <= pi/2 − theta_in): a
  //    logarithmic warp a = a0 (exp(k t) − 1), Gauss–Legendre in t (equal resolution at every
  //    scale of the lobe down to a0), and the periodic trapezoid rule in b (spectral);
  //  - beyond, the arc above the horizon, |b| <= b_max(a), with Gauss–Legendre in b and a
  //    cosine map in a that clusters nodes at both ends, where b_max has square-root
  //    behaviour (so the integrand is smooth in the mapped coordinate).
  const double theta = std::clamp(theta_in, 0.0, M_PI / 2);
  const Vec3 l = Direction(theta, 0);
  const Vec3 r(-l.x(), 0, l.z());
  const Vec3 e1(l.z(), 0, l.x()), e2 = Vec3::UnitY();  // r, e1, e2 orthonormal; e1.z >= 0
  constexpr int kOrder = 8;
  constexpr double kSmallestAngle = 1e-3;  // radians: the warp's scale near the peak
  const int radial_panels = std::max(2, options.theta_steps / 2);
  const int nb = options.phi_steps;

  Rgb sum = Rgb::Zero();
  // Full circles.
  const double a_full = M_PI / 2 - theta;
  if (a_full > 0) {
    const double k = std::log1p(a_full / kSmallestAngle);
    const QuadratureRule t_rule = CompositeGaussLegendre(radial_panels, kOrder, 0, 1);
    for (std::size_t i = 0; i < t_rule.nodes.size(); ++i) {
      const double e = std::exp(k * t_rule.nodes[i]);
      const double a = kSmallestAngle * (e - 1), da_dt = kSmallestAngle * k * e;
      const double ca = std::cos(a), sa = std::sin(a);
      Rgb ring = Rgb::Zero();
      for (int j = 0; j < nb; ++j) {
        const double b = (j + 0.5) * 2 * M_PI / nb;
        const Vec3 v = ca * r + sa * (std::cos(b) * e1 + std::sin(b) * e2);
        if (v.z() > 0) ring += brdf.Eval(l, v, kNormal) * v.z();
      }
      sum += ring * (2 * M_PI / nb) * sa * da_dt * t_rule.weights[i];
    }
  }
  // Arcs cut by the horizon, up to the radius where the circle sinks below it.
  const double a_end = std::min(M_PI, M_PI / 2 + theta);
  if (theta > 0 && a_end > a_full) {
    const QuadratureRule u_rule =
        CompositeGaussLegendre(std::max(1, radial_panels / 2), kOrder, 0, 1);
    const QuadratureRule b_unit = GaussLegendre(std::max(2, nb / 2), -1, 1);
    for (std::size_t i = 0; i < u_rule.nodes.size(); ++i) {
      const double u = u_rule.nodes[i];
      const double a = a_full + (a_end - a_full) * 0.5 * (1 - std::cos(M_PI * u));
      const double da_du = (a_end - a_full) * 0.5 * M_PI * std::sin(M_PI * u);
      const double ca = std::cos(a), sa = std::sin(a);
      // v.z = ca r.z + sa cos(b) e1.z > 0  <=>  cos(b) > −ca r.z / (sa e1.z).
      const double b_max = std::acos(std::clamp(-ca * r.z() / (sa * e1.z()), -1.0, 1.0));
      Rgb arc = Rgb::Zero();
      for (std::size_t j = 0; j < b_unit.nodes.size(); ++j) {
        const double b = b_max * b_unit.nodes[j];
        const Vec3 v = ca * r + sa * (std::cos(b) * e1 + std::sin(b) * e2);
        if (v.z() > 0) arc += brdf.Eval(l, v, kNormal) * (v.z() * b_unit.weights[j]);
      }
      sum += arc * b_max * sa * da_du * u_rule.weights[i];
    }
  }
  return sum;
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
