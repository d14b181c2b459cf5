#include "reconstruct/fit_ladder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/format.h"
#include "common/parallel.h"
#include "reconstruct/energy.h"
#include "reconstruct/log_loss.h"

namespace brdfrig::reconstruct {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Fitting order: ggx before microfacet (the table starts from the GGX fit of the same data).
constexpr brdf::ModelKind kLadder[] = {
    brdf::ModelKind::kSeed,     brdf::ModelKind::kSeedConstrained, brdf::ModelKind::kGgx,
    brdf::ModelKind::kBeckmann, brdf::ModelKind::kMicrofacet,      brdf::ModelKind::kPrior};

// Every position's samples, each position weighing the same in the fit: a sample's weight is
// its pixel count, and how many pixels a photo gives the cut-out depends on the camera's
// distance and angle, not on how much that photo's part of the BRDF matters. Left as pixels, a
// steep view (few pixels) counts a third of a near-normal one, and a lobe shape that does not
// fit every photo bends towards the near-normal ones.
std::vector<DirectionSample> Pool(const std::vector<const PositionSamples*>& positions) {
  std::vector<DirectionSample> all;
  for (const PositionSamples* p : positions) {
    double total = 0;
    for (const DirectionSample& s : p->directions.samples) total += s.weight;
    if (!(total > 0)) continue;
    const double scale = 1000.0 / total;
    for (DirectionSample s : p->directions.samples) {
      s.weight *= scale;
      all.push_back(s);
    }
  }
  return all;
}

double Score(const brdf::Material& material, const PositionSamples& held_out,
             const MicrofacetFitOptions& options) {
  const auto& samples = held_out.directions.samples;
  const double score =
      LogLossRms(*material.Model(), samples, LossEpsilon(samples, options.epsilon_fraction));
  return std::isfinite(score) ? score : kInf;
}

std::size_t ModelBytes(brdf::Material m) {
  m.fit = nlohmann::json::object();
  m.ladder = nlohmann::json::array();
  m.provenance = nlohmann::json::object();
  m.diagnostics.clear();
  return brdf::SerializeMaterial(m).size();
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Fits every rung in `kinds` to `positions`; failed rungs are nullopt with the reason.
struct FoldFits {
  std::vector<std::optional<brdf::Material>> materials;
  std::vector<std::string> errors;
};

// Every rung is refitted without the held-out position, the slice rungs too: what their slices
// share (pooled incidence angles, seed_constrained's diffuse floor and energy scale) would
// otherwise carry the held-out photo into its own prediction, and score the slice rungs
// better than the rungs that are refitted honestly.
FoldFits FitAll(const std::vector<brdf::ModelKind>& kinds,
                const std::vector<const PositionSamples*>& positions, const LadderOptions& options,
                const std::vector<const brdf::MicrofacetModelParams*>& starts) {
  FoldFits out;
  out.materials.reserve(kinds.size());  // fold_ggx points into it
  const brdf::MicrofacetModelParams* fold_ggx = nullptr;
  for (std::size_t r = 0; r < kinds.size(); ++r) {
    try {
      const brdf::ModelKind kind = kinds[r];
      const brdf::MicrofacetModelParams* start =
          kind == brdf::ModelKind::kMicrofacet ? fold_ggx : starts[r];
      out.materials.push_back(FitRung(kind, positions, options, false, nullptr, start));
      out.errors.emplace_back();
      if (kind == brdf::ModelKind::kGgx) fold_ggx = &out.materials.back()->microfacet;
    } catch (const Error& e) {
      out.materials.push_back(std::nullopt);
      out.errors.emplace_back(e.what());
    }
  }
  return out;
}

}  // namespace

void LadderOptions::Validate() const {
  if (!model.empty() && brdf::ParseModelKind(model) == brdf::ModelKind::kGltf) {
    // Not a rung: every reconstruction writes the chosen rung's glTF version beside it.
    throw OptionsError(
        "LadderOptions.model = gltf; not a rung of the ladder (the glTF version "
        "of the chosen rung is written with every material)");
  }
  slice.Validate();
  microfacet.Validate();
  prior.Validate();
}

brdf::Material FitRung(brdf::ModelKind kind, const std::vector<const PositionSamples*>& positions,
                       const LadderOptions& options, bool final, RungResult* details,
                       const brdf::MicrofacetModelParams* ggx_start) {
  if (positions.empty()) throw Error("no positions to fit");
  if (brdf::IsSliceKind(kind)) {
    SliceFitOptions slice = options.slice;
    slice.covariance = slice.covariance && final;
    SeedFit seed = FitSeed(positions, slice, kind == brdf::ModelKind::kSeedConstrained);
    if (details) {
      details->warnings = seed.warnings;
      details->slices_from_positions = seed.slices_from_positions;
    }
    (void)seed.material.Model();  // validates
    return seed.material;
  }
  if (kind == brdf::ModelKind::kPrior) return FitPriorRung(positions, options.prior);
  MicrofacetFitOptions mf = options.microfacet;
  mf.covariance = mf.covariance && final;
  const std::vector<DirectionSample> samples = Pool(positions);
  MicrofacetFit fit;
  if (kind == brdf::ModelKind::kMicrofacet) {
    MicrofacetFit ggx;
    if (!ggx_start) {
      ggx = FitAnalyticMicrofacet(samples, brdf::Distribution::kGgx, mf);
      ggx_start = &ggx.params;
    }
    fit = FitTableMicrofacet(samples, *ggx_start, mf);
  } else {
    const brdf::Distribution d =
        kind == brdf::ModelKind::kGgx ? brdf::Distribution::kGgx : brdf::Distribution::kBeckmann;
    fit = FitAnalyticMicrofacet(samples, d, mf,
                                ggx_start && ggx_start->distribution == d ? ggx_start : nullptr);
  }
  brdf::Material material;
  material.kind = kind;
  material.microfacet = fit.params;
  material.fit = fit.diagnostics;
  material.fit["warnings"] = fit.warnings;
  nlohmann::json used = nlohmann::json::array();
  for (const PositionSamples* p : positions) used.push_back(p->index);
  material.fit["positions"] = used;
  (void)material.Model();  // validates
  return material;
}

LadderResult FitLadder(const std::vector<PositionSamples>& fit_positions,
                       const std::vector<PositionSamples>& validation_positions,
                       const LadderOptions& options,
                       const std::function<void(const std::string&)>& say) {
  options.Validate();
  std::vector<brdf::ModelKind> kinds;
  if (options.model.empty()) {
    kinds.assign(std::begin(kLadder), std::end(kLadder));
  } else {
    kinds = {brdf::ParseModelKind(options.model)};
  }
  std::vector<const PositionSamples*> all;
  for (const PositionSamples& p : fit_positions) all.push_back(&p);

  LadderResult result;
  result.rungs.reserve(kinds.size());  // pointers into it are kept below
  // Every rung on every fit position: the model that is written.
  const brdf::MicrofacetModelParams* ggx_params = nullptr;
  for (brdf::ModelKind kind : kinds) {
    RungResult rung;
    rung.kind = kind;
    if (say) say(std::string("fitting the ") + brdf::ModelKindName(kind) + " rung");
    const auto start = std::chrono::steady_clock::now();
    try {
      rung.material = FitRung(kind, all, options, true, &rung,
                              kind == brdf::ModelKind::kMicrofacet ? ggx_params : nullptr);
      rung.fitted = true;
    } catch (const Error& e) {
      rung.error = e.what();
      if (say) say(std::string(brdf::ModelKindName(kind)) + " rung failed: " + e.what());
    }
    rung.fit_seconds = Seconds(start);
    if (rung.fitted) rung.size_bytes = ModelBytes(rung.material);
    result.rungs.push_back(std::move(rung));
    if (kind == brdf::ModelKind::kGgx && result.rungs.back().fitted) {
      ggx_params = &result.rungs.back().material.microfacet;
    }
  }
  std::vector<const brdf::MicrofacetModelParams*> starts;
  for (const RungResult& r : result.rungs) {
    starts.push_back(r.fitted && !brdf::IsSliceKind(r.kind) ? &r.material.microfacet : nullptr);
  }

  const bool folds = options.validate && options.model.empty() && fit_positions.size() >= 2;
  if (folds) {
    if (say) say("validating: " + std::to_string(fit_positions.size()) + " leave-one-out folds");
    std::vector<FoldFits> fold_fits(fit_positions.size());
    ParallelFor(fit_positions.size(), [&](std::size_t begin, std::size_t end) {
      for (std::size_t f = begin; f < end; ++f) {
        std::vector<const PositionSamples*> train;
        for (std::size_t i = 0; i < fit_positions.size(); ++i) {
          if (i != f) train.push_back(&fit_positions[i]);
        }
        fold_fits[f] = FitAll(kinds, train, options, starts);
      }
    });
    for (std::size_t f = 0; f < fit_positions.size(); ++f) {
      for (std::size_t r = 0; r < kinds.size(); ++r) {
        const auto& m = fold_fits[f].materials[r];
        result.rungs[r].fold_positions.push_back(fit_positions[f].index);
        result.rungs[r].fold_scores.push_back(m ? Score(*m, fit_positions[f], options.microfacet)
                                                : kInf);
      }
    }
  }
  for (RungResult& rung : result.rungs) {
    for (const PositionSamples& v : validation_positions) {
      rung.validation_scores.push_back(rung.fitted ? Score(rung.material, v, options.microfacet)
                                                   : kInf);
    }
    std::vector<double> all_scores = rung.fold_scores;
    all_scores.insert(all_scores.end(), rung.validation_scores.begin(),
                      rung.validation_scores.end());
    if (!rung.fitted) {
      rung.score = kInf;
    } else if (all_scores.empty()) {
      // Nothing held out: the fit's own residual (the only figure there is).
      rung.score = brdf::IsSliceKind(rung.kind)
                       ? LogLossRms(*rung.material.Model(), Pool(all),
                                    LossEpsilon(Pool(all), options.microfacet.epsilon_fraction))
                       : rung.material.fit.value("residual", kInf);
    } else {
      double sum = 0;
      for (double s : all_scores) sum += s;
      rung.score = sum / static_cast<double>(all_scores.size());
    }
  }
  // A model that reflects more light than it receives cannot be the default (the seed's
  // slices are kept as the paper wrote them and may): it is chosen only when forced, or when no
  // rung conserves energy (then the ladder says so).
  for (RungResult& rung : result.rungs) {
    if (rung.fitted) rung.max_albedo = MaxAlbedo(*rung.material.Model()).albedo;
  }
  // A material unlike the prior's training set is left to the data and the compact forms.
  const auto choose = [&](bool strict) {
    for (std::size_t r = 0; r < result.rungs.size(); ++r) {
      const RungResult& rung = result.rungs[r];
      if (!rung.fitted || (strict && !rung.ConservesEnergy())) continue;
      if (strict && OutsidePrior(rung.material)) continue;
      if (result.chosen < 0 || rung.score < result.rungs[result.chosen].score) {
        result.chosen = static_cast<int>(r);
      }
    }
  };
  choose(/*strict=*/true);
  if (result.chosen < 0) choose(/*strict=*/false);
  // When a rung is forced its energy is in the ladder (max_albedo); when the choice had to fall
  // back to a model that creates energy, say so.
  if (options.model.empty() && result.chosen >= 0 &&
      !result.rungs[result.chosen].ConservesEnergy()) {
    result.rungs[result.chosen].warnings.push_back(
        "no rung conserves energy: the chosen model's directional albedo reaches " +
        std::to_string(result.rungs[result.chosen].max_albedo));
  }
  if (result.chosen < 0) {
    std::string reasons;
    for (const RungResult& r : result.rungs) {
      reasons += std::string("\n  ") + brdf::ModelKindName(r.kind) + ": " + r.error;
    }
    throw Error("no model could be fitted:" + reasons);
  }
  result.rungs[result.chosen].chosen = true;
  return result;
}

nlohmann::json LadderResult::Json() const {
  nlohmann::json out = nlohmann::json::array();
  const auto finite = [](double x) -> nlohmann::json {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
  };
  for (const RungResult& r : rungs) {
    nlohmann::json folds = nlohmann::json::array();
    for (std::size_t f = 0; f < r.fold_scores.size(); ++f) {
      folds.push_back(
          {{"held_out_position", r.fold_positions[f]}, {"score", finite(r.fold_scores[f])}});
    }
    nlohmann::json validation = nlohmann::json::array();
    for (double s : r.validation_scores) validation.push_back(finite(s));
    nlohmann::json j = {
        {"kind", brdf::ModelKindName(r.kind)},
        {"score", finite(r.score)},
        {"score_protocol", r.fold_scores.empty() && r.validation_scores.empty()
                               ? "fit residual (nothing held out)"
                               : "mean held-out weighted RMS of ln(eps + f cos_i) residuals"},
        {"lopo_folds", folds},
        {"validation_scores", validation},
        {"size_bytes", r.size_bytes},
        {"chosen", r.chosen},
        {"max_albedo", r.max_albedo}};
    if (!r.fitted) j["error"] = r.error;
    out.push_back(j);
  }
  return out;
}

std::string LadderResult::Summary() const {
  std::ostringstream out;
  out << "model ladder (held-out log RMS, lower is better; per fold; fit time; size):\n";
  for (const RungResult& r : rungs) {
    out << "  " << (r.chosen ? "* " : "  ") << brdf::ModelKindName(r.kind) << ": ";
    if (!r.fitted) {
      out << "failed (" << r.error << ")\n";
      continue;
    }
    out << Fixed(r.score, 3) << " [";
    for (std::size_t f = 0; f < r.fold_scores.size(); ++f) {
      out << (f ? " " : "") << Fixed(r.fold_scores[f], 3);
    }
    out << "]";
    if (!r.validation_scores.empty()) {
      out << " validation [";
      for (std::size_t v = 0; v < r.validation_scores.size(); ++v) {
        out << (v ? " " : "") << Fixed(r.validation_scores[v], 3);
      }
      out << "]";
    }
    out << ", " << Fixed(r.fit_seconds, 2) << " s, " << r.size_bytes << " B\n";
  }
  return out.str();
}

}  // namespace brdfrig::reconstruct
