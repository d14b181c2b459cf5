#include "reconstruct/prior_rung.h"

#include "common/error.h"

namespace brdfrig::reconstruct {

brdf::Material FitPriorRung(const std::vector<const PositionSamples*>& positions,
                            const PriorRungOptions& options) {
  options.Validate();
  const prior::MeasuredPrior& p = options.prior ? *options.prior : prior::DefaultPrior();
  std::vector<prior::Observation> observations;
  nlohmann::json used = nlohmann::json::array();
  for (const PositionSamples* position : positions) {
    double total = 0;
    for (const DirectionSample& s : position->directions.samples) total += s.weight;
    if (!(total > 0)) continue;
    used.push_back(position->index);
    for (const DirectionSample& s : position->directions.samples) {
      observations.push_back({s.l, s.v, brdf::Rgb(s.f[0], s.f[1], s.f[2]),
                              s.weight * 1000.0 / total});
    }
  }
  const prior::PriorFitResult fit = prior::FitPrior(p, observations, options.fit);
  brdf::Material material;
  material.kind = brdf::ModelKind::kPrior;
  material.table_grid = p.grid;
  material.table = fit.table;
  material.fit = {{"prior", p.name},
                  {"prior_training_materials", p.training.size()},
                  {"prior_components", p.Components()},
                  {"observations", fit.observations},
                  {"misfit", fit.misfit},
                  {"misfit_limit", options.fit.misfit_limit},
                  {"outside_prior", fit.outside_prior},
                  {"positions", used}};
  nlohmann::json warnings = nlohmann::json::array();
  if (fit.outside_prior) {
    warnings.push_back("the samples leave residuals " + std::to_string(fit.misfit) +
                       " times the prior's noise level: the material lies outside what the "
                       "prior has seen, so this rung is not chosen by default");
  }
  material.fit["warnings"] = warnings;
  // What is written is the 16-bit table: keep exactly that in memory too, so a material used
  // before and after writing is the same model.
  return brdf::ParseMaterial(brdf::SerializeMaterial(material), "prior rung");
}

bool OutsidePrior(const brdf::Material& material) {
  return material.kind == brdf::ModelKind::kPrior && material.fit.value("outside_prior", false);
}

}  // namespace brdfrig::reconstruct
