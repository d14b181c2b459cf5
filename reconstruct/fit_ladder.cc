#include "reconstruct/fit_ladder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

#include "common/error.h"
#include "common/format.h"
#include "reconstruct/energy.h"
#include "reconstruct/fit_schedule.h"
#include "reconstruct/log_loss.h"
#include "reconstruct/stage_timer.h"

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

// Whether a photo says anything a rung can be scored on: a value, or a bound.
bool Scorable(const PositionSamples& p) {
  return !p.directions.samples.empty() || !p.directions.bounds.empty();
}

double Score(const brdf::Material& material, const PositionSamples& held_out,
             const MicrofacetFitOptions& options) {
  const auto& samples = held_out.directions.samples;
  const auto& bounds = held_out.directions.bounds;
  // The photo's blocks below the noise floor count as what they are, upper bounds: a rung that
  // is bright where the photo saw nothing is contradicted by it (a black mirror's compact fits
  // put a lobe where the photo is dark). eps from the values, or from the bounds when the photo
  // holds nothing else.
  const double score =
      LogLossRms(*material.Model(), samples,
                 LossEpsilon(samples.empty() ? bounds : samples, options.epsilon_fraction), bounds);
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

// A fit's expected cost relative to the others, for the order of the tasks only (measured on
// the default capture: the table rung costs most, the GGX rung's six starts next; a fold's
// analytic fit starts from the full fit and needs far fewer iterations).
double ExpectedCost(brdf::ModelKind kind, bool fold) {
  switch (kind) {
    case brdf::ModelKind::kMicrofacet:
      return 1.6;
    case brdf::ModelKind::kGgx:
      return fold ? 0.35 : 2.2;
    case brdf::ModelKind::kBeckmann:
      return fold ? 0.1 : 1.0;
    case brdf::ModelKind::kSeed:
    case brdf::ModelKind::kSeedConstrained:
      return 0.35;
    default:
      return 0.05;
  }
}

// One fit of a fold: nullopt with the reason when it failed.
struct FoldFit {
  std::optional<brdf::Material> material;
  std::string error;
  double cpu_seconds = 0;
};

}  // namespace

void LadderOptions::Validate() const {
  if (!model.empty() && brdf::ParseModelKind(model) == brdf::ModelKind::kGltf) {
    // Not a rung: every reconstruction writes the chosen rung's glTF version beside it.
    throw OptionsError(
        "LadderOptions.model = gltf; not a rung of the ladder (the glTF version "
        "of the chosen rung is written with every material)");
  }
  if (!(prior_allowance >= 1)) {
    throw OptionsError("LadderOptions.prior_allowance = " + std::to_string(prior_allowance) +
                       "; must be >= 1");
  }
  slice.Validate();
  microfacet.Validate();
  prior.Validate();
}

brdf::Material FitRung(brdf::ModelKind kind, const std::vector<const PositionSamples*>& positions,
                       const LadderOptions& options, bool final, RungResult* details,
                       const brdf::MicrofacetModelParams* ggx_start, SliceFitMemo* slice_memo) {
  if (positions.empty()) throw Error("no positions to fit");
  if (brdf::IsSliceKind(kind)) {
    SliceFitOptions slice = options.slice;
    slice.covariance = slice.covariance && final;
    SeedFit seed =
        FitSeed(positions, slice, kind == brdf::ModelKind::kSeedConstrained, {}, slice_memo);
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
  mf.albedo_diagnostic = mf.albedo_diagnostic && final;
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
  const int rungs = static_cast<int>(kinds.size());
  result.rungs.resize(kinds.size());
  int ggx = -1;  // the GGX rung's index, if it is on the ladder: it starts the table rung
  for (int r = 0; r < rungs; ++r) {
    result.rungs[r].kind = kinds[r];
    if (kinds[r] == brdf::ModelKind::kGgx) ggx = r;
  }
  // Every rung is refitted without the held-out position, the slice rungs too: what their
  // slices share (pooled incidence angles, seed_constrained's diffuse floor and energy scale)
  // would otherwise carry the held-out photo into its own prediction, and score the slice
  // rungs better than the rungs that are refitted honestly.
  // A position wholly below the noise floor is held out too: its bounds say where the material
  // is dark, which a rung may contradict. Folds need two positions with values, so that every
  // fold still has one to fit.
  std::vector<int> held_out;
  int with_values = 0;
  for (int i = 0; i < static_cast<int>(fit_positions.size()); ++i) {
    if (Scorable(fit_positions[i])) held_out.push_back(i);
    if (!fit_positions[i].directions.samples.empty()) ++with_values;
  }
  const bool validate = options.validate && options.model.empty() && with_values >= 2;
  const int folds = validate ? static_cast<int>(held_out.size()) : 0;
  std::vector<std::vector<const PositionSamples*>> train(folds);
  for (int f = 0; f < folds; ++f) {
    for (int i = 0; i < static_cast<int>(fit_positions.size()); ++i) {
      if (i != held_out[f]) train[f].push_back(&fit_positions[i]);
    }
  }
  SliceFitMemo slice_memo;  // the folds refit most slices unchanged
  std::vector<std::vector<FoldFit>> fold_fits(folds, std::vector<FoldFit>(kinds.size()));
  std::mutex say_mutex;
  const auto say_locked = [&](const std::string& message) {
    if (!say) return;
    std::lock_guard lock(say_mutex);
    say(message);
  };

  // Tasks: 0 .. rungs−1 fit every rung on every fit position (the model that is written);
  // rungs + f·rungs + r fits rung r on fold f's positions.
  std::vector<FitTask> tasks;
  for (int r = 0; r < rungs; ++r) {
    FitTask task;
    task.expected_cost = ExpectedCost(kinds[r], false);
    if (kinds[r] == brdf::ModelKind::kMicrofacet && ggx >= 0) task.after = {ggx};
    task.run = [&, r] {
      RungResult& rung = result.rungs[r];
      say_locked(std::string("fitting the ") + brdf::ModelKindName(rung.kind) + " rung");
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = ThreadCpuSeconds();
      const RungResult* ggx_rung = ggx >= 0 ? &result.rungs[ggx] : nullptr;
      const brdf::MicrofacetModelParams* ggx_start =
          rung.kind == brdf::ModelKind::kMicrofacet && ggx_rung && ggx_rung->fitted
              ? &ggx_rung->material.microfacet
              : nullptr;
      try {
        rung.material = FitRung(rung.kind, all, options, true, &rung, ggx_start, &slice_memo);
        rung.fitted = true;
      } catch (const Error& e) {
        rung.error = e.what();
        say_locked(std::string(brdf::ModelKindName(rung.kind)) + " rung failed: " + e.what());
      }
      rung.fit_seconds = Seconds(start);
      rung.fit_cpu_seconds = ThreadCpuSeconds() - cpu_start;
      if (rung.fitted) rung.size_bytes = ModelBytes(rung.material);
    };
    tasks.push_back(std::move(task));
  }
  for (int f = 0; f < folds; ++f) {
    for (int r = 0; r < rungs; ++r) {
      FitTask task;
      const brdf::ModelKind kind = kinds[r];
      task.expected_cost = ExpectedCost(kind, true);
      // The analytic rungs start from their full fit; the table rung from the fold's GGX fit.
      const bool from_full = kind == brdf::ModelKind::kGgx || kind == brdf::ModelKind::kBeckmann;
      if (from_full) task.after = {r};
      if (kind == brdf::ModelKind::kMicrofacet && ggx >= 0) task.after = {rungs + f * rungs + ggx};
      task.run = [&, f, r, kind, from_full] {
        FoldFit& out = fold_fits[f][r];
        const double cpu_start = ThreadCpuSeconds();
        const brdf::MicrofacetModelParams* start = nullptr;
        if (from_full && result.rungs[r].fitted) start = &result.rungs[r].material.microfacet;
        if (kind == brdf::ModelKind::kMicrofacet && ggx >= 0 && fold_fits[f][ggx].material) {
          start = &fold_fits[f][ggx].material->microfacet;
        }
        try {
          out.material = FitRung(kind, train[f], options, false, nullptr, start, &slice_memo);
        } catch (const Error& e) {
          out.error = e.what();
        }
        out.cpu_seconds = ThreadCpuSeconds() - cpu_start;
      };
      tasks.push_back(std::move(task));
    }
  }
  if (folds > 0) {
    say_locked("fitting " + std::to_string(rungs) + " rungs, and each on " + std::to_string(folds) +
               " leave-one-out folds");
  }
  RunFitTasks(tasks);

  for (int f = 0; f < folds; ++f) {
    for (int r = 0; r < rungs; ++r) {
      const FoldFit& fit = fold_fits[f][r];
      RungResult& rung = result.rungs[r];
      rung.fold_cpu_seconds += fit.cpu_seconds;
      const PositionSamples& held = fit_positions[held_out[f]];
      rung.fold_positions.push_back(held.index);
      rung.fold_scores.push_back(fit.material ? Score(*fit.material, held, options.microfacet)
                                              : kInf);
    }
  }
  for (RungResult& rung : result.rungs) {
    for (const PositionSamples& v : validation_positions) {
      if (!Scorable(v)) continue;  // an empty photo: nothing to score
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
    if (!rung.fitted) continue;
    // The microfacet rungs' fits computed it for their diagnostics (the same model).
    const nlohmann::json& fit = rung.material.fit;
    rung.max_albedo = !brdf::IsSliceKind(rung.kind) && fit.contains("albedo_max")
                          ? fit["albedo_max"].get<double>()
                          : MaxAlbedo(*rung.material.Model()).albedo;
  }
  // A material unlike the prior's training set is left to the data and the compact forms.
  const auto compared = [&](const RungResult& rung) {
    const bool allowed = validate && rung.kind == brdf::ModelKind::kPrior;
    return allowed ? rung.score / options.prior_allowance : rung.score;
  };
  const auto choose = [&](bool strict) {
    for (std::size_t r = 0; r < result.rungs.size(); ++r) {
      const RungResult& rung = result.rungs[r];
      if (!rung.fitted || (strict && !rung.ConservesEnergy())) continue;
      if (strict && OutsidePrior(rung.material)) continue;
      if (result.chosen < 0 || compared(rung) < compared(result.rungs[result.chosen])) {
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
                               : "mean held-out weighted RMS of ln(eps + f cos_i) residuals "
                                 "(blocks below the noise floor: only where the rung is brighter)"},
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
