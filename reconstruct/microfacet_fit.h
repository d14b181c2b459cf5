// Fitting the microfacet rungs of the ladder to direction samples of every position at once
// (Ceres, Levenberg–Marquardt, the loss of reconstruct/log_loss.h under a Huber loss), with
// the formulas of brdf/microfacet_terms.h:
//
//   ggx, beckmann  rho_d (per channel), f0 (per channel), alpha. Parameterized in logs with
//                  bounds (rho_d in [0, 1], f0 in [1e-4, 1], alpha in [1e-3, 1]); started from a
//                  few alphas with rho_d and f0 read off the data; the best start is kept.
//   microfacet     ln D at `table_knots` knots over [0, max observed theta_h], monotone by
//                  construction (ln D_{k+1} = ln D_k − exp(s_k)); a GGX tail beyond the table
//                  whose roughness matches the drop of ln D over the table's last interval;
//                  Smith G with its own roughness (weakly held to its start); f0 and rho_d per
//                  channel; `fresnel_knots` Fresnel correction knots shared by the channels,
//                  pulled towards 0 by a prior; a smoothness prior on ln D's second
//                  differences. D is normalized through one extra residual tying a free ln Z to
//                  TableNormalization(...) (ln D_0 is held: the scale of D is a gauge). Started
//                  from the GGX fit.
//
// After the fit the specular term is scaled down where the albedo would exceed 1
// (reconstruct/energy.h), and the diagnostics say what the data cannot determine.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdf/microfacet_model.h"
#include "reconstruct/direction_samples.h"

namespace brdfrig::reconstruct {

struct MicrofacetFitOptions {
  int table_knots = 32;
  int fresnel_knots = 4;           // 0 = no correction
  double fresnel_prior = 0.1;      // weight of the pull of the correction knots towards 0
  double smoothness = 0.03;        // weight of the second-difference prior on ln D
  double epsilon_fraction = 0.01;  // of the 10th percentile of f·cos_i (log_loss.h)
  double loss_scale = 0.25;        // Huber scale in ln units (0 = plain least squares)
  int max_iterations = 100;
  bool covariance = true;  // parameter std-devs (analytic rungs)
  // The fit's albedo_max diagnostic (directional albedo over 0°–85°, written in Material::fit);
  // the ladder's folds turn it off: their fits are only scored, never written.
  bool albedo_diagnostic = true;
  bool energy_check = true;  // scale the specular term down where the albedo exceeds 1
  void Validate() const;
};

struct MicrofacetFit {
  brdf::MicrofacetModelParams params;
  double residual = 0;  // weighted RMS of the log residual (log_loss.h), all samples
  int sample_count = 0;
  double seconds = 0;
  std::array<bool, 3> diffuse_observed{};  // samples where the diffuse term dominates
  double max_theta_h = 0;                  // observed (radians)
  double theta_d_min = 0, theta_d_max = 0;
  double energy_scale = 1;  // < 1 when the specular term had to be scaled down
  std::vector<std::string> warnings;
  nlohmann::json diagnostics;  // what goes into Material::fit
};

// Throws brdfrig::Error with too few samples. `start`: a fit of similar data to start from
// (one start instead of several; the ladder's validation folds use the full fit).
MicrofacetFit FitAnalyticMicrofacet(const std::vector<DirectionSample>& samples,
                                    brdf::Distribution distribution,
                                    const MicrofacetFitOptions& options,
                                    const brdf::MicrofacetModelParams* start = nullptr);

// `start`: a GGX fit of the same samples (its rho_d, f0 and alpha start the table).
MicrofacetFit FitTableMicrofacet(const std::vector<DirectionSample>& samples,
                                 const brdf::MicrofacetModelParams& start,
                                 const MicrofacetFitOptions& options);

}  // namespace brdfrig::reconstruct
