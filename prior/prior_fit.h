// A material's table from its measured samples and the prior: the samples decide where the
// photos saw the material, the prior fills in the rest.
//
//  1. Maximum a posteriori coefficients, per channel: minimise
//        Σ_o w_o (q_o − μ(x_o) − b(x_o)·c)² / σ² + (c − m)ᵀ P (c − m)
//     (q_o the sample's mapped value, μ and b the mean and components interpolated at its
//     coordinates, σ the prior's noise level). The coefficients' prior (m, P) is local to the
//     training channels the data resemble (PriorFitOptions::bandwidth); with bandwidth 0 it is
//     m = 0, P = diag(1/s_k²), s_k² the coefficients' variances over the training set.
//     An observation may be an upper bound (a region darker than the photos' noise floor):
//     it adds the same term only while the fit lies above it, a one-sided penalty, solved by
//     re-solving with the violated bounds as observations until that set stops changing.
//  2. Where the photos saw the material, the table follows them: each node moves by the
//     weighted mean of the residuals of the samples around it, shrunk by the prior's
//     correction weight (a node with little data keeps the prior's value). A material's
//     departure from the components is smooth, so the residuals first move the nodes within a
//     few steps of the samples (a Gaussian spread, `correction_reach`), then each sample's own
//     nodes take what is left.
//  3. Misfit: the weighted RMS residual of step 1 in q (σ is a regularisation weight chosen by
//     leave-one-material-out, not the photos' noise, so the misfit is judged in q itself). A
//     material unlike every training material leaves residuals the components cannot explain:
//     left-out training materials leave 0.02–0.3 from noise-free plan samples (docs/prior.md),
//     photo noise adds a few hundredths; above `misfit_limit` the fit says the material lies
//     outside the prior and the ladder does not choose this rung by default.
#pragma once

#include <vector>

#include "brdf/rusinkiewicz_table.h"
#include "prior/measured_prior.h"

namespace brdfrig::prior {

// One measured BRDF sample in the local frame (z = normal).
struct Observation {
  brdf::Vec3 l = brdf::Vec3::UnitZ(), v = brdf::Vec3::UnitZ();
  brdf::Rgb f = brdf::Rgb::Zero();
  double weight = 1;
  bool upper_bound = false;  // f is the largest the material can be there (not a value)
};

struct PriorFitOptions {
  double misfit_limit = 0.5;  // residual RMS in q above which the material is outside the prior
  bool correct = true;        // step 2
  // Step 2's reach: the residuals first spread over neighbouring nodes with a Gaussian of this
  // standard deviation in node steps along each axis of the grid, then each sample's own
  // stencil takes what is left (0: that second pass alone). docs/prior.md, stop 42.
  double correction_reach = 1;
  // The prior of step 1. > 0: local to the training channels the data resemble, each a
  // Gaussian of this width in units of the coefficients' spread over the training set (1: the
  // best of 0.2–1.4 left one material out, docs/prior.md); 0: one Gaussian over all of them.
  double bandwidth = 1;
  void Validate() const;
};

struct PriorFitResult {
  brdf::TableValues table;  // q per channel and node
  std::array<Eigen::VectorXd, 3> coefficients;
  double misfit = 0;  // step 3, the worst channel
  bool outside_prior = false;
  int observations = 0;  // values, not bounds
  int bounds = 0;
  int bounds_active = 0;  // bounds the solution presses against (worst channel)
  // With a local prior: per channel, each training channel's share of it (rows as the prior's
  // training_coefficients: material-major, RGB); empty with bandwidth 0.
  std::array<Eigen::VectorXd, 3> neighbour_weights;
};

// Throws brdfrig::Error when there is no value (not bound) with positive weight.
PriorFitResult FitPrior(const MeasuredPrior& prior, const std::vector<Observation>& observations,
                        const PriorFitOptions& options = {});

}  // namespace brdfrig::prior
