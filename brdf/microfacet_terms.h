// The terms of every microfacet model of the ladder, written once as templates so that the CPU
// model (double) and the Ceres fits (ceres::Jet) evaluate the very same formulas:
//
//     f = rho_d / pi + F(theta_d) · D(theta_h) · G1(theta_i) G1(theta_o) / (4 cos_i cos_o)
//
// D is a GGX or Beckmann distribution, or a table of ln D over theta_h (the data-driven rung):
// `knots` values at theta_h = (k / (knots − 1))² · max_theta_h (dense near the peak, like MERL's
// theta_h axis), linear in ln D between knots, continued beyond max_theta_h by a GGX tail of
// roughness `tail_alpha` matched to the table's last value. F is Schlick's approximation per
// channel, optionally times exp(c(theta_d)) with c linear between knots at equal theta_d steps
// over [0, pi/2] (c(0) is the first knot). G1 is Smith's masking term, GGX form, for the GGX and
// table rungs and Walter's rational approximation for Beckmann.
//
// Arguments that come from the sample geometry are double; parameters are T.
#pragma once

#include <algorithm>
#include <cmath>

namespace brdfrig::brdf::microfacet {

template <typename T>
T GgxD(double cos_h, const T& alpha) {
  const T a2 = alpha * alpha;
  const double c2 = cos_h * cos_h;
  const T denom = a2 * c2 + (1.0 - c2);
  return a2 / (M_PI * denom * denom);
}

template <typename T>
T LogGgxD(double cos_h, const T& alpha) {
  using std::log;
  const T a2 = alpha * alpha;
  const double c2 = cos_h * cos_h;
  return log(a2) - std::log(M_PI) - 2.0 * log(a2 * c2 + (1.0 - c2));
}

template <typename T>
T BeckmannD(double cos_h, const T& alpha) {
  using std::exp;
  const T a2 = alpha * alpha;
  const double c2 = std::max(cos_h * cos_h, 1e-300);
  const double tan2 = (1 - c2) / c2;
  return exp(-tan2 / a2) / (M_PI * a2 * c2 * c2);
}

// Smith masking for GGX: 2c / (c + sqrt(a² + (1 − a²) c²)).
template <typename T>
T GgxG1(double cos_t, const T& alpha) {
  using std::sqrt;
  const T a2 = alpha * alpha;
  const double c2 = cos_t * cos_t;
  return 2.0 * cos_t / (cos_t + sqrt(a2 * (1.0 - c2) + c2));
}

// Smith masking for Beckmann, Walter et al. (2007) rational fit (error < 0.35 %).
template <typename T>
T BeckmannG1(double cos_t, const T& alpha) {
  const double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
  if (sin_t <= 0) return T(1.0);
  const T a = cos_t / (alpha * sin_t);
  if (a >= 1.6) return T(1.0);
  return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

template <typename T>
T Schlick(const T& f0, double cos_d) {
  const double m = 1 - std::clamp(cos_d, 0.0, 1.0);
  const double m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// c(theta_d): linear between `count` knots at theta_d = k/(count − 1) · pi/2; 0 when count is 0.
template <typename T>
T FresnelCorrection(const T* knots, int count, double theta_d) {
  if (count <= 0) return T(0.0);
  if (count == 1) return knots[0];
  const double x = std::clamp(theta_d / (M_PI / 2), 0.0, 1.0) * (count - 1);
  const int k = std::min(static_cast<int>(x), count - 2);
  const double t = x - k;
  return (1 - t) * knots[k] + t * knots[k + 1];
}

// theta_h of table knot k.
inline double TableKnotThetaH(int k, int knots, double max_theta_h) {
  const double u = static_cast<double>(k) / (knots - 1);
  return u * u * max_theta_h;
}

// Where theta_h falls in the table: ln D = (1 − t) ln D[k] + t ln D[k + 1] inside the table;
// beyond max_theta_h (tail), ln D = ln D[knots − 1] + the tail's GGX drop from max_theta_h.
// The fits use it to know which knots a sample depends on.
struct TablePosition {
  int k = 0;
  double t = 0;
  bool tail = false;
};

inline TablePosition LocateInTable(int knots, double max_theta_h, double theta_h) {
  if (theta_h >= max_theta_h) return {knots - 1, 0, true};
  const double x = std::sqrt(std::max(theta_h, 0.0) / max_theta_h) * (knots - 1);
  const int k = std::min(static_cast<int>(x), knots - 2);
  return {k, x - k, false};
}

// ln D at a located theta_h from the knot values it depends on (lo = D[k], hi = D[k + 1],
// both D[knots − 1] in the tail).
template <typename T>
T TableLogDAt(const TablePosition& at, const T& log_d_lo, const T& log_d_hi, double max_theta_h,
              const T& tail_alpha, double theta_h) {
  if (at.tail) {
    return log_d_lo + LogGgxD(std::cos(theta_h), tail_alpha) -
           LogGgxD(std::cos(max_theta_h), tail_alpha);
  }
  return (1 - at.t) * log_d_lo + at.t * log_d_hi;
}

// ln D(theta_h) of the table rung (before normalization).
template <typename T>
T TableLogD(const T* log_d, int knots, double max_theta_h, const T& tail_alpha, double theta_h) {
  const TablePosition at = LocateInTable(knots, max_theta_h, theta_h);
  return TableLogDAt(at, log_d[at.k], log_d[at.tail ? at.k : at.k + 1], max_theta_h, tail_alpha,
                     theta_h);
}

// Projected-area normalization of the table's D: 2 pi ∫ D(theta_h) cos sin dtheta_h over
// [0, pi/2]. A physical D integrates to 1. Fixed Gauss–Legendre points: 4 per table interval
// in the table's own sqrt-warped coordinate, 48 over the tail in a log-warped coordinate
// (the tail is steep just past max_theta_h).
template <typename T>
T TableNormalization(const T* log_d, int knots, double max_theta_h, const T& tail_alpha) {
  using std::exp;
  static constexpr double kNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                       0.8611363115940526};
  static constexpr double kWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                         0.3478548451374538};
  T sum(0.0);
  // Table part: theta = u² · max_theta_h, dtheta = 2 u max_theta_h du.
  for (int k = 0; k + 1 < knots; ++k) {
    const double u0 = static_cast<double>(k) / (knots - 1),
                 u1 = static_cast<double>(k + 1) / (knots - 1);
    for (int q = 0; q < 4; ++q) {
      const double u = 0.5 * (u0 + u1) + 0.5 * (u1 - u0) * kNodes[q];
      const double theta = u * u * max_theta_h;
      const double jacobian = 2 * u * max_theta_h * 0.5 * (u1 - u0) * kWeights[q];
      sum += exp(TableLogD(log_d, knots, max_theta_h, tail_alpha, theta)) *
             (std::cos(theta) * std::sin(theta) * jacobian);
    }
  }
  // Tail: s = ln(theta − max_theta_h + eps) uniform, 12 intervals × 4 points.
  const double end = M_PI / 2;
  if (max_theta_h < end) {
    const double eps = 1e-4;
    const double s0 = std::log(eps), s1 = std::log(end - max_theta_h + eps);
    const int intervals = 12;
    for (int i = 0; i < intervals; ++i) {
      const double a = s0 + (s1 - s0) * i / intervals, b = s0 + (s1 - s0) * (i + 1) / intervals;
      for (int q = 0; q < 4; ++q) {
        const double s = 0.5 * (a + b) + 0.5 * (b - a) * kNodes[q];
        const double theta = max_theta_h + std::exp(s) - eps;
        const double jacobian = std::exp(s) * 0.5 * (b - a) * kWeights[q];
        sum += exp(TableLogD(log_d, knots, max_theta_h, tail_alpha, theta)) *
               (std::cos(theta) * std::sin(theta) * jacobian);
      }
    }
  }
  return 2 * M_PI * sum;
}

}  // namespace brdfrig::brdf::microfacet
