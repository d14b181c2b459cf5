// BRDF-space figures of a fit against the truth: the log-cosine error over the hemisphere pair
// and the directional albedo at incidence angles from 0° to 80°, grazing included (where
// Fresnel is unconstrained by mirror-only plans and the albedo can be off by orders of
// magnitude while the images barely show it).
#pragma once

#include <string>
#include <vector>

#include "brdf/brdf.h"

namespace brdfrig::evaluate {

struct BrdfFiguresOptions {
  std::vector<double> albedo_angles_deg = {0, 15, 30, 45, 60, 75, 80};
  void Validate() const;  // throws OptionsError
};

struct AlbedoAtAngle {
  double theta_in_deg = 0;
  brdf::Rgb truth = brdf::Rgb::Zero(), fitted = brdf::Rgb::Zero();  // ∫ f cos θo dωo
  // max over channels of |fitted − truth| / truth (a channel with truth 0 counts
  // |fitted| / 1e-6, so a fit that invents light where there is none is not forgiven).
  double relative_error = 0;
};

struct BrdfFigures {
  double log_cosine_error = 0;  // brdf::LogCosineError(truth, fitted)
  std::vector<AlbedoAtAngle> albedo;
  double max_albedo_error = 0;  // over angles
  std::string protocol;
  std::string Report() const;  // one line
};

BrdfFigures CompareBrdf(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                        const BrdfFiguresOptions& options = {});

// The directional-albedo error that decides "albedo within x %" (docs/results.md): over the
// channels and `angles_deg`, the (fitted − truth) / truth largest in magnitude, with its sign
// (> 0: the fit reflects too much).
double WorstAlbedoError(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                        const std::vector<double>& angles_deg = {0, 15, 30, 45, 60, 75});

}  // namespace brdfrig::evaluate
