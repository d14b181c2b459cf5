// Numbers that say how good a BRDF (fit) is.
#pragma once

#include "brdf/brdf.h"

namespace brdfrig::brdf {

struct MetricOptions {
  int theta_steps = 32;  // quadrature resolution per angle
  int phi_steps = 64;
  void Validate() const;  // throws OptionsError
};

// Cosine-weighted log error over the hemisphere pair (Löw et al. 2012 style), per channel mean:
//   sqrt( sum (ln(1 + f_a cos_i) − ln(1 + f_b cos_i))^2 sin(theta_i) sin(theta_o) dΩ / norm ).
double LogCosineError(const Brdf& a, const Brdf& b, const MetricOptions& options = {});

// Directional albedo ∫ f cos(theta_o) dω_o for light at theta_in; <= 1 for energy conservation.
Rgb DirectionalAlbedo(const Brdf& brdf, double theta_in, const MetricOptions& options = {});

// Max over a direction grid of |f(l,v) − f(v,l)| / max(f(l,v), f(v,l), tiny).
double ReciprocityError(const Brdf& brdf, const MetricOptions& options = {});

}  // namespace brdfrig::brdf
