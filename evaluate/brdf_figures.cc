#include "evaluate/brdf_figures.h"

#include <algorithm>
#include <cmath>

#include "brdf/metrics.h"
#include "common/error.h"
#include "common/format.h"

namespace brdfrig::evaluate {

void BrdfFiguresOptions::Validate() const {
  if (albedo_angles_deg.empty()) throw OptionsError("BRDF figures: albedo_angles_deg is empty");
  for (double a : albedo_angles_deg) {
    if (!(a >= 0 && a < 90)) {
      throw OptionsError("BRDF figures: albedo angle " + Fixed(a, 3) + " deg must be in [0, 90)");
    }
  }
}

std::string BrdfFigures::Report() const {
  std::string out = "BRDF: log-cosine error " + Fixed(log_cosine_error, 4) +
                    ", albedo relative error max " + Fixed(max_albedo_error, 3) + " [";
  for (std::size_t i = 0; i < albedo.size(); ++i) {
    out += (i ? ", " : "") + Fixed(albedo[i].theta_in_deg, 0) +
           "°: " + Fixed(albedo[i].relative_error, 3);
  }
  return out + "] (" + protocol + ")";
}

BrdfFigures CompareBrdf(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                        const BrdfFiguresOptions& options) {
  options.Validate();
  BrdfFigures figures;
  figures.protocol =
      "log-cosine error: brdf::LogCosineError; albedo: brdf::DirectionalAlbedo, relative error "
      "per channel, max over channels";
  figures.log_cosine_error = brdf::LogCosineError(truth, fitted);
  for (double angle : options.albedo_angles_deg) {
    AlbedoAtAngle a;
    a.theta_in_deg = angle;
    a.truth = brdf::DirectionalAlbedo(truth, angle * M_PI / 180);
    a.fitted = brdf::DirectionalAlbedo(fitted, angle * M_PI / 180);
    const brdf::Rgb error = (a.fitted - a.truth).abs() / a.truth.max(1e-6);
    // A NaN albedo is as wrong as it gets.
    a.relative_error = error.isNaN().any() ? INFINITY : error.maxCoeff();
    figures.max_albedo_error = std::max(figures.max_albedo_error, a.relative_error);
    figures.albedo.push_back(a);
  }
  return figures;
}

double WorstAlbedoError(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                        const std::vector<double>& angles_deg) {
  double worst = 0;
  for (const double angle : angles_deg) {
    const brdf::Rgb a = brdf::DirectionalAlbedo(truth, angle * M_PI / 180);
    const brdf::Rgb b = brdf::DirectionalAlbedo(fitted, angle * M_PI / 180);
    for (int c = 0; c < 3; ++c) {
      const double error = (b[c] - a[c]) / std::max(a[c], 1e-6);
      if (!std::isfinite(error)) return INFINITY;
      if (std::abs(error) > std::abs(worst)) worst = error;
    }
  }
  return worst;
}

}  // namespace brdfrig::evaluate
