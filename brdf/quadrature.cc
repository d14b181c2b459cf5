#include "brdf/quadrature.h"

#include <cassert>
#include <cmath>

namespace brdfrig::brdf {

QuadratureRule GaussLegendre(int n, double a, double b) {
  assert(n >= 1);
  QuadratureRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  // Newton's method on P_n from Chebyshev-like starting points; the roots are symmetric, so
  // each pair is computed once.
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      // Three-term recurrence for P_n(x) and P_{n-1}(x).
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);  // P_n'(x)
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    const double w = 2 / ((1 - x * x) * dp * dp);
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    rule.nodes[i] = mid - half * x;
    rule.nodes[n - 1 - i] = mid + half * x;
    rule.weights[i] = rule.weights[n - 1 - i] = half * w;
  }
  return rule;
}

QuadratureRule CompositeGaussLegendre(int panels, int n, double a, double b) {
  assert(panels >= 1);
  QuadratureRule rule;
  const double width = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    const QuadratureRule panel = GaussLegendre(n, a + p * width, a + (p + 1) * width);
    rule.nodes.insert(rule.nodes.end(), panel.nodes.begin(), panel.nodes.end());
    rule.weights.insert(rule.weights.end(), panel.weights.begin(), panel.weights.end());
  }
  return rule;
}

}  // namespace brdfrig::brdf
