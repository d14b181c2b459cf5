// Stage 3 of the reconstruction: every rung of the model ladder fitted to the measured
// positions, each scored by how well it predicts photos it was not fitted to, and the best
// one chosen.
//
// Scores use the fits' loss (reconstruct/log_loss.h, eps from the held-out data): the
// weighted RMS of ln(eps + f_model·cos_i) − ln(eps + f_data·cos_i) over a held-out position's
// direction samples, and over its blocks below the noise floor where the rung is brighter than
// them (upper bounds; a photo with only those is held out too, while two photos have values).
// Leave-one-position-out (LOPO): each fit position in turn is left out, the rung is fitted to
// the others and scored on it; the rung's score is the mean over folds.
// Validation positions (the plan's, when the capture has them) are never fitted; every rung
// fitted to all fit positions is scored on them, and those scores count with the folds'.
// A fold whose fit fails scores +inf (the rung cannot be fitted from that subset).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdf/material_file.h"
#include "reconstruct/microfacet_fit.h"
#include "reconstruct/prior_rung.h"
#include "reconstruct/seed_fit.h"
#include "reconstruct/slice_fit.h"

namespace brdfrig::reconstruct {

struct LadderOptions {
  // Empty: fit every rung and choose by validation. A kind name ("seed", "ggx", ...): fit only
  // that rung, no validation.
  std::string model;
  SliceFitOptions slice;
  MicrofacetFitOptions microfacet;
  PriorRungOptions prior;
  bool validate = true;  // LOPO folds (false: every rung fitted once, the choice by residual)
  // The measured prior's validation score is divided by this before the rungs are compared.
  // The folds of a designed plan share no (θh, θd) cell (docs/ladder_choice.md), so each asks a
  // rung to predict a patch no remaining photo sees: the compact forms' one smooth curve
  // extrapolates calmly there and scores well even where, fitted to all photos, the prior is
  // better. Measured over the 80 measured and 9 analytic materials' studies (each measured one
  // judged by the prior built without it): 1 is validation as it was (sphere mean 30.9 / 49.1
  // dB), 2 gives 31.6 / 48.4 dB and albedo within 10 % on 27 of 80 measured materials instead
  // of 20; the measured figure is flat from 1.75 to 3, the analytic one falls past 2.
  double prior_allowance = 2;
  void Validate() const;
};

struct RungResult {
  brdf::ModelKind kind = brdf::ModelKind::kSeed;
  brdf::Material material;  // fitted to every fit position (diagnostics in slices / fit)
  bool fitted = false;
  std::string error;                // why the rung could not be fitted (fitted == false)
  double fit_seconds = 0;           // wall time of the final fit (not in Json(): see below)
  double fit_cpu_seconds = 0;       // its CPU time
  double fold_cpu_seconds = 0;      // CPU time of this rung's fits in the folds, summed
  double score = 0;                 // mean held-out score (lower is better); +inf when unscored
  std::vector<int> fold_positions;  // the held-out position of each fold
  std::vector<double> fold_scores;  // LOPO
  std::vector<double> validation_scores;  // one per validation position
  std::size_t size_bytes = 0;             // the model in material.json (without fit/ladder json)
  bool chosen = false;
  double max_albedo = 0;  // directional albedo's maximum over 0°–85° (fitted rungs)
  // Energy conservation (albedo <= 1 within quadrature tolerance): required of the default.
  bool ConservesEnergy() const { return max_albedo <= 1 + 1e-3; }
  std::vector<std::string> warnings;     // the slice rungs' fit-wide warnings
  nlohmann::json slices_from_positions;  // slice rungs
};

struct LadderResult {
  std::vector<RungResult> rungs;
  int chosen = -1;  // index into rungs
  // What goes into Material::ladder. Wall times are left out (they are in Summary()): a
  // capture reprocessed gives the same material.json bytes (reconstruct/batch.h).
  nlohmann::json Json() const;
  std::string Summary() const;  // one line per rung
};

// `fit_positions`: the positions the rungs are fitted to; `validation_positions`: scored only.
// Throws brdfrig::Error when no rung can be fitted.
LadderResult FitLadder(const std::vector<PositionSamples>& fit_positions,
                       const std::vector<PositionSamples>& validation_positions,
                       const LadderOptions& options,
                       const std::function<void(const std::string&)>& say = {});

// One rung fitted to the given positions (`final`: with covariance and diagnostics; folds skip
// them; `slice_memo`: the slice rungs' fits to reuse, may be null). Throws brdfrig::Error when
// it cannot be fitted.
brdf::Material FitRung(brdf::ModelKind kind, const std::vector<const PositionSamples*>& positions,
                       const LadderOptions& options, bool final, RungResult* details = nullptr,
                       const brdf::MicrofacetModelParams* ggx_start = nullptr,
                       SliceFitMemo* slice_memo = nullptr);

}  // namespace brdfrig::reconstruct
