// The ladder's `prior` rung: a Rusinkiewicz table fitted to the positions' direction samples
// under the measured prior (prior/prior_fit.h). Each position's samples weigh the same in
// total (1000, as in the microfacet fits), the unit the prior's noise level is stated in.
#pragma once

#include <vector>

#include "brdf/material_file.h"
#include "prior/measured_prior.h"
#include "prior/prior_fit.h"
#include "reconstruct/seed_fit.h"

namespace brdfrig::reconstruct {

struct PriorRungOptions {
  const prior::MeasuredPrior* prior = nullptr;  // nullptr: the shipped prior (DefaultPrior)
  prior::PriorFitOptions fit;
  void Validate() const { fit.Validate(); }
};

// Throws brdfrig::Error when the prior cannot be read or no sample is usable.
brdf::Material FitPriorRung(const std::vector<const PositionSamples*>& positions,
                            const PriorRungOptions& options);

// True when the fit said the material lies outside what the prior has seen.
bool OutsidePrior(const brdf::Material& material);

}  // namespace brdfrig::reconstruct
