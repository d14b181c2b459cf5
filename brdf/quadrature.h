// Gauss–Legendre rules for the BRDF metrics' integrals.
#pragma once

#include <vector>

namespace brdfrig::brdf {

struct QuadratureRule {
  std::vector<double> nodes;    // in [a, b]
  std::vector<double> weights;  // sum to b − a
};

// The n-point Gauss–Legendre rule on [a, b] (exact for polynomials of degree 2n − 1).
QuadratureRule GaussLegendre(int n, double a, double b);

// `panels` equal panels of an n-point rule each on [a, b]: robust where the integrand is smooth
// only piecewise at the scale of a panel.
QuadratureRule CompositeGaussLegendre(int panels, int n, double a, double b);

}  // namespace brdfrig::brdf
