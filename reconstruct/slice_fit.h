// Fitting one slice of the seed's model to a position's BRDF samples, per colour channel, with
// Ceres (Levenberg–Marquardt). Parameterized so the constraints hold by construction:
//   A2 = exp(a), A1 = A2 + exp(b), h = exp(s), x0 free,
// with residuals in log space (the lobe spans orders of magnitude), a Cauchy loss against
// outliers, a data-driven start, and a covariance estimate. What the data cannot determine is
// said, not guessed: an unreached tail (A2), an unresolved edge (h at the angular resolution),
// an unobserved peak (A1), no lobe at all.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "brdf/slice_model.h"
#include "reconstruct/samples.h"

namespace brdfrig::reconstruct {

struct SliceFitOptions {
  int max_iterations = 200;
  double function_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
  double loss_scale = 0.2;  // Cauchy scale, in ln(f) units (0 = plain least squares)
  bool covariance = true;
  void Validate() const;
};

struct ChannelFit {
  brdf::LobeParams params;
  std::array<double, 4> stddev{};  // A1, A2, h, x0; NaN where the covariance is unavailable
  double rms_log_residual = 0;
  int iterations = 0;
};

struct SliceFit {
  brdf::Slice slice;
  std::array<ChannelFit, 3> channel;  // R, G, B
  int sample_count = 0;               // samples with f > 0 used by the fit
  double theta_min = 0, theta_max = 0;
  bool a2_observed = true;  // samples reach the lobe's tail
  bool a1_observed = true;  // samples near the mirror direction
  bool h_resolved = true;   // the lobe edge is wider than the angular resolution
  bool flat = false;        // no lobe (A1 ≈ A2)
  std::vector<std::string> warnings;
};

// `fixed_a2`: per channel (R, G, B), hold A2 at this value (used to share A2 across slices when
// a slice's tail is unobserved). Throws brdfrig::Error when there are too few samples.
SliceFit FitSlice(const BrdfSamples& samples, const SliceFitOptions& options,
                  const std::optional<std::array<double, 3>>& fixed_a2 = std::nullopt);

}  // namespace brdfrig::reconstruct
