#include "jobs/ladder_section.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "common/angles.h"
#include "common/format.h"

namespace brdfrig::jobs {
namespace {

const char* KindDescription(brdf::ModelKind kind) {
  switch (kind) {
    case brdf::ModelKind::kSeed:
      return "the seed's slice model";
    case brdf::ModelKind::kSeedConstrained:
      return "the seed's slices with one shared diffuse level, energy-limited";
    case brdf::ModelKind::kMicrofacet:
      return "data-driven microfacet (tabulated D)";
    case brdf::ModelKind::kGgx:
      return "GGX + Lambert, Schlick Fresnel";
    case brdf::ModelKind::kBeckmann:
      return "Beckmann + Lambert, Schlick Fresnel";
    case brdf::ModelKind::kPrior:
      return "measured prior: a Rusinkiewicz table from the samples and learned materials";
    case brdf::ModelKind::kGltf:
      return "glTF 2.0 metal-rough BRDF (KHR_materials_ior, KHR_materials_specular)";
  }
  return "?";
}

std::string Score(double s) { return std::isfinite(s) ? Fixed(s, 4) : "unscored"; }

std::string Scores(const std::vector<double>& scores) {
  if (scores.empty()) return "-";
  std::string out;
  for (double s : scores) out += (out.empty() ? "" : " ") + Score(s);
  return out;
}

std::string RgbText(const brdf::Rgb& c, int decimals) {
  return Fixed(c[0], decimals) + " " + Fixed(c[1], decimals) + " " + Fixed(c[2], decimals);
}

// The seed kinds' slices, green channel with its standard deviations.
evaluate::Table SliceTable(const brdf::Material& m) {
  evaluate::Table t{"Chosen rung's slices (A1, A2 in 1/sr; h, x0 in degrees), green ± 1 sigma",
                    {"theta_in (deg)", "A1", "A2", "h", "x0", "residual (ln)", "warnings"},
                    {}};
  for (std::size_t i = 0; i < m.slices.size(); ++i) {
    const brdf::LobeParams& g = m.slices[i].channel[1];
    const brdf::SliceDiagnostics d =
        i < m.diagnostics.size() ? m.diagnostics[i] : brdf::SliceDiagnostics{};
    const auto& sd = d.stddev[1];
    std::string warnings;
    for (const std::string& w : d.warnings) warnings += (warnings.empty() ? "" : "; ") + w;
    t.rows.push_back({Fixed(Degrees(m.slices[i].theta_in), 2),
                      Fixed(g.a1, 4) + " ± " + Fixed(sd[0], 4),
                      Fixed(g.a2, 4) + " ± " + Fixed(sd[1], 4),
                      Fixed(Degrees(g.h), 3) + " ± " + Fixed(Degrees(sd[2]), 3),
                      Fixed(Degrees(g.x0), 3) + " ± " + Fixed(Degrees(sd[3]), 3),
                      Fixed(d.residual, 4), warnings.empty() ? "-" : warnings});
  }
  return t;
}

// A fit diagnostic as table cells: numbers to 5 significant digits, arrays of scalars on one
// line, objects one row per member ("relative_stddev.alpha"), so the table stays readable
// whatever the fit chose to record.
std::string ScalarText(const nlohmann::json& value) {
  if (value.is_number_float()) {
    std::ostringstream out;
    out.precision(5);
    out << value.get<double>();
    return out.str();
  }
  return value.is_string() ? value.get<std::string>() : value.dump();
}

void AddFitRows(const std::string& key, const nlohmann::json& value, evaluate::Table* t) {
  if (value.is_object()) {
    for (const auto& [k, v] : value.items()) AddFitRows(key + "." + k, v, t);
    return;
  }
  if (value.is_array() &&
      std::none_of(value.begin(), value.end(), [](const auto& v) { return v.is_structured(); })) {
    std::string text;
    for (const auto& v : value) text += (text.empty() ? "" : " ") + ScalarText(v);
    t->rows.push_back({key, text.empty() ? "-" : text});
    return;
  }
  t->rows.push_back({key, ScalarText(value)});
}

// The microfacet kinds' parameters and the fit's own diagnostics (Material::fit, as written).
evaluate::Table MicrofacetTable(const brdf::Material& m) {
  const brdf::MicrofacetModelParams& p = m.microfacet;
  evaluate::Table t{"Chosen rung's parameters and fit diagnostics", {"quantity", "value"}, {}};
  t.rows.push_back({"rho_d (R G B)", RgbText(p.diffuse, 4)});
  t.rows.push_back({"f0 (R G B)", RgbText(p.f0, 4)});
  t.rows.push_back(
      {m.kind == brdf::ModelKind::kMicrofacet ? "alpha (tail)" : "alpha", Fixed(p.alpha, 4)});
  if (!p.fresnel_knots.empty()) {
    t.rows.push_back({"Fresnel knots", std::to_string(p.fresnel_knots.size())});
  }
  if (!p.log_d.empty()) {
    t.rows.push_back({"ln D knots", std::to_string(p.log_d.size()) + " to theta_h " +
                                        Fixed(Degrees(p.max_theta_h), 2) + "°"});
    t.rows.push_back({"shadowing alpha", Fixed(p.shadowing_alpha, 4)});
  }
  for (const auto& [key, value] : m.fit.items()) {
    if (key != "warnings") AddFitRows(key, value, &t);
  }
  return t;
}

}  // namespace

std::string ChosenModelPhrase(const reconstruct::LadderResult& ladder) {
  if (ladder.chosen < 0) return "no model";
  const brdf::ModelKind kind = ladder.rungs[static_cast<std::size_t>(ladder.chosen)].kind;
  std::string phrase =
      std::string("the ") + brdf::ModelKindName(kind) + " rung (" + KindDescription(kind) + ")";
  if (ladder.rungs.size() > 1) {
    phrase += ", chosen by validation among " + std::to_string(ladder.rungs.size()) + " rungs";
  } else {
    phrase += ", the only rung fitted";
  }
  return phrase;
}

evaluate::ReportSection LadderSection(const reconstruct::LadderResult& ladder) {
  evaluate::ReportSection s{"Model ladder", {}, {}, {}, {}};
  s.paragraphs.push_back(
      "Every rung fitted to the fit positions and scored on photos it was not fitted to: "
      "leave-one-position-out folds (each fit position left out in turn, the rung refitted to "
      "the others) and the plan's validation photos (never fitted). Score: weighted RMS of "
      "ln(eps + f cos_i) residuals over the held-out direction samples, lower is better; the "
      "rung with the lowest mean is written. Without anything held out the score is the fit "
      "residual.");
  s.paragraphs.push_back("Written: " + ChosenModelPhrase(ladder) + ".");
  evaluate::Table t{"Rungs",
                    {"rung", "model", "mean score", "LOPO folds", "validation photos",
                     "size (bytes)", "fit time (s)", "chosen"},
                    {}};
  for (const reconstruct::RungResult& r : ladder.rungs) {
    const std::string name = brdf::ModelKindName(r.kind);
    if (!r.fitted) {
      t.rows.push_back({name, KindDescription(r.kind), "not fitted: " + r.error, "-", "-", "-",
                        Fixed(r.fit_seconds, 2), "no"});
      continue;
    }
    t.rows.push_back({name, KindDescription(r.kind), Score(r.score), Scores(r.fold_scores),
                      Scores(r.validation_scores), std::to_string(r.size_bytes),
                      Fixed(r.fit_seconds, 2), r.chosen ? "yes" : "no"});
  }
  s.tables.push_back(t);
  if (ladder.chosen < 0) return s;
  const reconstruct::RungResult& chosen = ladder.rungs[static_cast<std::size_t>(ladder.chosen)];
  if (brdf::IsSliceKind(chosen.kind)) {
    s.tables.push_back(SliceTable(chosen.material));
  } else {
    s.tables.push_back(MicrofacetTable(chosen.material));
    for (const auto& w : chosen.material.fit.value("warnings", nlohmann::json::array())) {
      s.paragraphs.push_back("fit warning: " + w.get<std::string>());
    }
  }
  for (const std::string& w : chosen.warnings) s.paragraphs.push_back("fit warning: " + w);
  return s;
}

}  // namespace brdfrig::jobs
