#include "reconstruct/prior_rung.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "common/error.h"
#include "reconstruct/energy.h"

namespace brdfrig::reconstruct {
namespace {

// The training materials the local prior leaned on most (their share averaged over the three
// channels), largest first: what the fit says the sample is like.
nlohmann::json Resembles(const prior::MeasuredPrior& p, const prior::PriorFitResult& fit) {
  nlohmann::json out = nlohmann::json::array();
  if (fit.neighbour_weights[0].size() == 0) return out;
  std::vector<std::pair<double, std::size_t>> share(p.training.size());
  for (std::size_t m = 0; m < p.training.size(); ++m) {
    share[m] = {0.0, m};
    for (int ch = 0; ch < 3; ++ch) {  // any of its channels may resemble any of ours
      share[m].first +=
          fit.neighbour_weights[ch].segment(static_cast<Eigen::Index>(3 * m), 3).sum() / 3;
    }
  }
  std::sort(share.begin(), share.end(), std::greater<>());
  for (std::size_t i = 0; i < std::min<std::size_t>(3, share.size()); ++i) {
    if (share[i].first < 0.01) break;
    out.push_back({{"material", p.training[share[i].second].name},
                   {"share", std::round(share[i].first * 1000) / 1000}});
  }
  return out;
}

}  // namespace

brdf::Material FitPriorRung(const std::vector<const PositionSamples*>& positions,
                            const PriorRungOptions& options) {
  options.Validate();
  const prior::MeasuredPrior& p = options.prior ? *options.prior : prior::DefaultPrior();
  std::vector<prior::Observation> observations;
  nlohmann::json used = nlohmann::json::array();
  for (const PositionSamples* position : positions) {
    // Each position weighs the same, its pixels alike whether they gave values or bounds.
    const DirectionSamples& d = position->directions;
    double total = 0;
    for (const DirectionSample& s : d.samples) total += s.weight;
    for (const DirectionSample& s : d.bounds) total += s.weight;
    if (!(total > 0)) continue;
    used.push_back(position->index);
    for (const auto* kind : {&d.samples, &d.bounds}) {
      for (const DirectionSample& s : *kind) {
        observations.push_back({s.l, s.v, brdf::Rgb(s.f[0], s.f[1], s.f[2]),
                                s.weight * 1000.0 / total, kind == &d.bounds});
      }
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
                  {"bounds", fit.bounds},
                  {"bounds_active", fit.bounds_active},
                  {"prior_bandwidth", options.fit.bandwidth},
                  {"resembles", Resembles(p, fit)},
                  {"misfit", fit.misfit},
                  {"misfit_limit", options.fit.misfit_limit},
                  {"outside_prior", fit.outside_prior},
                  {"positions", used}};
  nlohmann::json warnings = nlohmann::json::array();
  if (fit.outside_prior) {
    warnings.push_back("the prior's components miss the samples by " + std::to_string(fit.misfit) +
                       " (RMS of ln(f cos cos + eps)): the material lies outside what the prior "
                       "has seen, so this rung is not chosen by default");
  }
  const double scale = LimitTableEnergy(material.table_grid, &material.table);
  material.fit["energy_scale"] = scale;
  if (scale > 1) {
    warnings.push_back(
        "the table reflected more light than it received at some incidence "
        "angles: scaled down there by up to " +
        std::to_string(scale));
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
