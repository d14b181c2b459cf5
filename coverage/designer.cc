#include "coverage/designer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "common/angles.h"
#include "common/error.h"
#include "common/format.h"
#include "common/parallel.h"
#include "coverage/prior_objective.h"
#include "prior/measured_prior.h"

namespace brdfrig::coverage {
namespace {

double AngleFromNormal(const geometry::Vec3& p) {
  return std::acos(std::clamp(p.normalized().z(), -1.0, 1.0));
}

// One candidate position with the objective's elements it covers.
struct Candidate {
  geometry::AxisPositions axes;
  PositionCoverage coverage;
  std::vector<int> elements;
  Eigen::MatrixXd information;  // the prior objective's (prior_objective.h)
};

class Objective {
 public:
  Objective(const DesignOptions& o) : o_(o) {
    const GridOptions& g = o.search_grid;
    cells_ = g.theta_h_bins * g.theta_d_bins;
    weights_.assign(cells_, o.cell_weight);
    weights_.resize(cells_ + g.theta_h_bins, o.theta_h_weight);
    weights_.resize(cells_ + g.theta_h_bins + g.theta_d_bins, o.theta_d_weight);
    retro_ = static_cast<int>(weights_.size());
    weights_.push_back(o.requirement_weight);
    grazing_ = retro_ + 1;
    weights_.push_back(o.requirement_weight);
    counts_.assign(weights_.size(), 0);
  }

  std::vector<int> Elements(const PositionCoverage& c) const {
    const GridOptions& g = o_.search_grid;
    std::vector<int> e = c.cells;
    // The marginals are smooth curves (a D table, a Fresnel curve): a bin is constrained by a
    // sample within `*_reach_bins` of it, so the marginal elements are the seen bins dilated.
    const auto dilate = [&](int bin, int reach, int bins, int offset) {
      for (int b = std::max(0, bin - reach); b <= std::min(bins - 1, bin + reach); ++b) {
        e.push_back(offset + b);
      }
    };
    for (const int cell : c.cells) {
      const int h = cell / g.theta_d_bins, d = cell % g.theta_d_bins;
      dilate(h, o_.theta_h_reach_bins, g.theta_h_bins, cells_);
      if (ThetaHEdge(h, g.theta_h_bins) < Radians(o_.peak_theta_h_deg)) {
        dilate(d, o_.theta_d_reach_bins, g.theta_d_bins, cells_ + g.theta_h_bins);
      }
    }
    if (c.theta_d_min <= Radians(o_.retro_theta_d_deg)) e.push_back(retro_);
    if (c.theta_in >= Radians(o_.grazing_theta_in_deg)) e.push_back(grazing_);
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    return e;
  }

  double Gain(const std::vector<int>& elements) const {
    double gain = 0;
    for (const int e : elements) {
      if (counts_[e] == 0) gain += weights_[e];
    }
    return gain;
  }
  void Add(const std::vector<int>& elements, int delta) {
    for (const int e : elements) counts_[e] += delta;
  }
  double Score() const {
    double s = 0;
    for (std::size_t e = 0; e < weights_.size(); ++e) s += counts_[e] > 0 ? weights_[e] : 0;
    return s;
  }
  double MaxScore() const {
    double s = 0;
    for (const double w : weights_) s += w;
    return s;
  }
  bool Covered(int e) const { return counts_[e] > 0; }
  int retro() const { return retro_; }
  int grazing() const { return grazing_; }

 private:
  const DesignOptions& o_;
  int cells_ = 0, retro_ = 0, grazing_ = 0;
  std::vector<double> weights_;
  std::vector<int> counts_;
};

// Axis values 0, ±step, ±2·step … within the limits (round numbers a person can read back);
// a full turn keeps one of its two equal ends.
std::vector<double> AxisValues(const geometry::RotationAxis& axis, double step) {
  std::vector<double> values;
  const int lo = static_cast<int>(std::ceil(axis.min / step - 1e-9));
  const int hi = static_cast<int>(std::floor(axis.max / step + 1e-9));
  const bool full_turn = axis.max - axis.min >= 2 * M_PI - 1e-9;
  for (int k = lo; k <= hi; ++k) {
    if (full_turn && k == lo && std::abs(k * step + 2 * M_PI - hi * step) < 1e-9) continue;
    values.push_back(k * step);
  }
  if (values.empty()) values.push_back(std::clamp(0.0, axis.min, axis.max));
  return values;
}

std::size_t GridSize(const geometry::RigGeometry& rig, double step) {
  std::size_t n = 1;
  for (const geometry::RotationAxis& axis : rig.axes) n *= AxisValues(axis, step).size();
  return n;
}

std::vector<geometry::AxisPositions> CandidateGrid(const geometry::RigGeometry& rig, double step) {
  std::vector<geometry::AxisPositions> grid(1);
  for (const geometry::RotationAxis& axis : rig.axes) {
    std::vector<geometry::AxisPositions> next;
    for (const geometry::AxisPositions& partial : grid) {
      for (const double v : AxisValues(axis, step)) {
        geometry::AxisPositions p = partial;
        p[axis.name] = v;
        next.push_back(std::move(p));
      }
    }
    grid = std::move(next);
  }
  return grid;
}

bool MakeCandidate(const geometry::RigGeometry& rig, const geometry::AxisPositions& axes,
                   const DesignOptions& o, const Objective& objective, Candidate* c,
                   const PriorObjective* prior = nullptr) {
  if (!CheckDesignConstraints(rig, axes, o).empty()) return false;
  c->axes = axes;
  c->coverage = PositionCoverageAt(rig, axes, o.search_grid);
  if (!c->coverage.observed) return false;
  c->elements = objective.Elements(c->coverage);
  if (prior) {
    c->information = prior->Information(rig, axes);
    if (c->information.size() == 0) return false;
  }
  return true;
}

// Tries the neighbours of `*best` at half and quarter steps along each axis, keeping any that
// raises `value` above `*best_value` (a local continuous refinement of a swap).
void RefineAmongNeighbours(const geometry::RigGeometry& rig, const DesignOptions& o,
                           const Objective& coverage, const PriorObjective* prior, double step,
                           const std::function<double(const Candidate&)>& value, Candidate* best,
                           double* best_value) {
  for (const double fraction : {0.5, 0.25}) {
    // Neighbours of the best so far (a copy: `*best` may change inside the loop).
    const geometry::AxisPositions base = best->axes;
    for (const auto& [name, angle] : base) {
      for (const double sign : {-1.0, 1.0}) {
        geometry::AxisPositions axes = base;
        axes[name] = angle + sign * fraction * step;
        Candidate c;
        if (!MakeCandidate(rig, axes, o, coverage, &c, prior)) continue;
        const double v = value(c);
        if (v > *best_value + 1e-12) *best = std::move(c), *best_value = v;
      }
    }
  }
}

// Greedy selection and swaps under the prior objective: each step takes the candidate that
// lowers the expected error most (prior_objective.h).
std::vector<Candidate> ChooseForPrior(const geometry::RigGeometry& rig, const DesignOptions& o,
                                      const Objective& coverage, const PriorObjective& prior,
                                      const std::vector<Candidate>& candidates, double step) {
  const int k = prior.components();
  std::vector<Candidate> chosen;
  Eigen::MatrixXd total = Eigen::MatrixXd::Zero(k, k);
  std::vector<double> errors(candidates.size());
  const auto best_of = [&](const Eigen::MatrixXd& base, double* error) {
    ParallelFor(candidates.size(), [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        errors[i] = prior.ExpectedError(base + candidates[i].information);
      }
    });
    // The first of equal minima: the same plan whatever the thread count.
    const auto best = std::min_element(errors.begin(), errors.end()) - errors.begin();
    *error = errors[best];
    return static_cast<std::size_t>(best);
  };
  for (int n = 0; n < o.count; ++n) {
    double error = 0;
    const std::size_t best = best_of(total, &error);
    total += candidates[best].information;
    chosen.push_back(candidates[best]);
  }
  // Each swap pass rescans every candidate for every slot (~10⁵ evaluations of K³): at most
  // two passes, which on the default rig is where the swaps stop improving.
  for (int pass = 0; pass < std::min(o.refine_passes, 2); ++pass) {
    bool changed = false;
    for (Candidate& slot : chosen) {
      const Eigen::MatrixXd rest = total - slot.information;
      double best_error = prior.ExpectedError(total);
      const double current = best_error;
      double error = 0;
      const std::size_t best = best_of(rest, &error);
      Candidate replacement = slot;
      if (error < best_error - 1e-12) replacement = candidates[best], best_error = error;
      double value = -best_error;
      RefineAmongNeighbours(
          rig, o, coverage, &prior, step,
          [&](const Candidate& c) { return -prior.ExpectedError(rest + c.information); },
          &replacement, &value);
      best_error = -value;
      if (best_error < current - 1e-12) {
        total = rest + replacement.information;
        slot = std::move(replacement);
        changed = true;
      }
    }
    if (!changed) break;
  }
  return chosen;
}

std::string Describe(const PositionCoverage& c, const DesignOptions& o) {
  std::string what;
  if (c.theta_h_min < Radians(0.5)) {
    what = "specular peak (θh from 0) at θd " + Fixed(Degrees(c.theta_d_min), 0) + "–" +
           Fixed(Degrees(c.theta_d_max), 0) + "°";
  } else {
    what = "off-specular θh " + Fixed(Degrees(c.theta_h_min), 0) + "–" +
           Fixed(Degrees(c.theta_h_max), 0) + "° at θd " + Fixed(Degrees(c.theta_d_min), 0) + "–" +
           Fixed(Degrees(c.theta_d_max), 0) + "°";
  }
  if (c.theta_d_min <= Radians(o.retro_theta_d_deg)) what += "; near retro-reflection";
  if (c.theta_in >= Radians(o.grazing_theta_in_deg)) {
    what += "; grazing light (θi " + Fixed(Degrees(c.theta_in), 0) + "°)";
  }
  return what;
}

// How a bigger cut-out or a closer light would change one photo: both widen the spread of l
// and v across the cut-out (about w/d radians), hence the patch in (θh, θd).
std::vector<WidenHint> WidenHints(const geometry::RigGeometry& rig,
                                  const geometry::AxisPositions& axes, const DesignOptions& o) {
  std::vector<WidenHint> hints;
  geometry::RigGeometry bigger = rig;
  bigger.target.cutout_width *= 1.5;
  bigger.target.cutout_height *= 1.5;
  WidenHint cut{"cut-out " + Fixed(bigger.target.cutout_width * 1000, 0) + " × " +
                    Fixed(bigger.target.cutout_height * 1000, 0) + " mm",
                0, CheckDesignConstraints(bigger, axes, o).empty()};
  if (cut.fits)
    cut.cells = static_cast<int>(PositionCoverageAt(bigger, axes, o.report_grid).cells.size());
  hints.push_back(cut);
  geometry::RigGeometry closer = rig;
  closer.light_position *= 0.6;  // scaled towards the cut-out's centre
  WidenHint light{"light at " + Fixed(closer.light_position.norm(), 2) + " m", 0, true};
  light.cells = static_cast<int>(PositionCoverageAt(closer, axes, o.report_grid).cells.size());
  hints.push_back(light);
  return hints;
}

}  // namespace

void DesignOptions::Validate() const {
  const auto range = [](const char* field, double value, double lo, double hi) {
    if (!(value >= lo && value <= hi)) {
      throw OptionsError("plan design: " + std::string(field) + " = " + Fixed(value, 3) +
                         " must be between " + Fixed(lo, 3) + " and " + Fixed(hi, 3));
    }
  };
  range("count", count, 1, 24);
  range("validation", validation, 0, 24);
  range("step_deg", step_deg, 1, 45);
  range("max_candidates", max_candidates, 100, 1000000);
  range("refine_passes", refine_passes, 0, 20);
  range("theta_h_reach_bins", theta_h_reach_bins, 0, 16);
  range("theta_d_reach_bins", theta_d_reach_bins, 0, 16);
  range("min_separation_deg", min_separation_deg, 0, 90);
  range("max_view_deg", max_view_deg, 10, 89);
  range("max_light_deg", max_light_deg, 10, 89.9);
  range("image_margin_px", image_margin_px, 0, 1000);
  range("peak_theta_h_deg", peak_theta_h_deg, 0.1, 45);
  range("retro_theta_d_deg", retro_theta_d_deg, 0, 45);
  range("grazing_theta_in_deg", grazing_theta_in_deg, 30, 89);
  for (const auto& [field, w] : {std::pair{"cell_weight", cell_weight},
                                 {"theta_h_weight", theta_h_weight},
                                 {"theta_d_weight", theta_d_weight},
                                 {"requirement_weight", requirement_weight}}) {
    range(field, w, 0, 1e6);
  }
  if (objective != "prior" && objective != "coverage") {
    throw OptionsError("plan design: objective = '" + objective +
                       "' must be 'prior' or 'coverage'");
  }
  range("prior_components", prior_components, 1, PriorObjective::kMaxComponents);
  search_grid.Validate();
  report_grid.Validate();
}

std::string CheckDesignConstraints(const geometry::RigGeometry& rig,
                                   const geometry::AxisPositions& axes, const DesignOptions& o) {
  for (const auto& [name, angle] : axes) {
    const geometry::RotationAxis* axis = rig.FindAxis(name);
    if (!axis) return "no axis '" + name + "'";
    if (angle < axis->min - 1e-9 || angle > axis->max + 1e-9) {
      return name + " outside its limits";
    }
  }
  const geometry::CameraPose pose = rig.CameraAt(axes);
  const geometry::Vec3 camera = pose.CenterInWorld();
  const geometry::Vec3 light = rig.LightAt(axes);
  if (camera.z() <= 0 || AngleFromNormal(camera) > Radians(o.max_view_deg)) {
    return "camera more than " + Fixed(o.max_view_deg, 0) + "° from the normal";
  }
  if (light.z() <= 0 || AngleFromNormal(light) > Radians(o.max_light_deg)) {
    return "light more than " + Fixed(o.max_light_deg, 0) + "° from the normal";
  }
  const double separation =
      std::acos(std::clamp(camera.normalized().dot(light.normalized()), -1.0, 1.0));
  if (separation < Radians(o.min_separation_deg)) {
    return "camera and light less than " + Fixed(o.min_separation_deg, 0) + "° apart";
  }
  const geometry::Intrinsics& k = rig.intrinsics;
  for (const double sx : {-0.5, 0.5}) {
    for (const double sy : {-0.5, 0.5}) {
      const geometry::Vec3 corner(sx * rig.target.cutout_width, sy * rig.target.cutout_height, 0);
      Eigen::Vector2d px;
      const double m = o.image_margin_px;
      if (!geometry::ProjectToPixel(k, pose, corner, &px) || px.x() < m || px.y() < m ||
          px.x() > k.width - 1 - m || px.y() > k.height - 1 - m) {
        return "a corner of the cut-out is outside the image";
      }
    }
  }
  return "";
}

std::vector<geometry::AxisPositions> PlanDesign::Positions() const {
  std::vector<geometry::AxisPositions> p;
  for (const DesignedPosition& d : positions) p.push_back(d.coverage.axes);
  return p;
}

std::vector<bool> PlanDesign::Validation() const {
  std::vector<bool> v;
  for (const DesignedPosition& d : positions) v.push_back(d.coverage.validation);
  return v;
}

PlanDesign DesignPlan(const geometry::RigGeometry& rig, const DesignOptions& options) {
  options.Validate();
  if (rig.axes.empty()) throw Error("plan design: the rig has no axis to move");
  PlanDesign design;
  design.options = options;
  double step = Radians(options.step_deg);
  while (GridSize(rig, step) > static_cast<std::size_t>(options.max_candidates)) step *= 1.25;
  design.step_deg = Degrees(step);

  Objective objective(options);
  std::optional<PriorObjective> prior;
  if (options.objective == "prior") {
    prior.emplace(options.prior ? *options.prior : prior::DefaultPrior(), options.prior_components,
                  options.search_grid.samples_per_side);
  }
  std::vector<Candidate> candidates;
  for (const geometry::AxisPositions& axes : CandidateGrid(rig, step)) {
    Candidate c;
    if (MakeCandidate(rig, axes, options, objective, &c, prior ? &*prior : nullptr)) {
      candidates.push_back(std::move(c));
    }
  }
  design.candidates = static_cast<int>(candidates.size());
  const int wanted = options.count + options.validation;
  if (static_cast<int>(candidates.size()) < wanted) {
    throw Error("plan design: the rig allows " + std::to_string(candidates.size()) +
                " positions that keep the cut-out in view (grid step " + Fixed(design.step_deg, 1) +
                "°), fewer than the " + std::to_string(wanted) + " asked for");
  }

  // Greedy: the candidate adding the most objective, `count` times.
  std::vector<Candidate> chosen;
  if (prior) {
    chosen = ChooseForPrior(rig, options, objective, *prior, candidates, step);
    for (const Candidate& c : chosen) objective.Add(c.elements, +1);
  }
  const auto pick_best = [&](double* gain) {
    std::size_t best = 0;
    *gain = -1;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const double g = objective.Gain(candidates[i].elements);
      if (g > *gain) *gain = g, best = i;
    }
    return best;
  };
  for (int n = prior ? options.count : 0; n < options.count; ++n) {
    double gain = 0;
    const std::size_t best = pick_best(&gain);
    objective.Add(candidates[best].elements, +1);
    chosen.push_back(candidates[best]);
  }
  // Swap search: retry each chosen position against every candidate and its own neighbours at
  // finer steps; stop when a pass changes nothing.
  for (int pass = 0; pass < (prior ? 0 : options.refine_passes); ++pass) {
    bool changed = false;
    for (Candidate& slot : chosen) {
      objective.Add(slot.elements, -1);
      const double current = objective.Gain(slot.elements);
      double gain = 0;
      const std::size_t best = pick_best(&gain);
      Candidate replacement = slot;
      double best_gain = current;
      if (gain > best_gain + 1e-9) replacement = candidates[best], best_gain = gain;
      RefineAmongNeighbours(
          rig, options, objective, nullptr, step,
          [&](const Candidate& c) { return objective.Gain(c.elements); }, &replacement, &best_gain);
      if (best_gain > current + 1e-9) {
        slot = std::move(replacement);
        changed = true;
      }
      objective.Add(slot.elements, +1);
    }
    if (!changed) break;
  }
  design.score = objective.Score();
  design.max_score = objective.MaxScore();
  design.has_retro = objective.Covered(objective.retro());
  design.has_grazing = objective.Covered(objective.grazing());
  design.objective = options.objective;
  if (prior) {
    Eigen::MatrixXd total = Eigen::MatrixXd::Zero(prior->components(), prior->components());
    for (const Candidate& c : chosen) total += c.information;
    design.prior_name = prior->prior().name;
    design.prior_only_rms = prior->RmsPerNode(prior->PriorError());
    design.expected_rms = prior->RmsPerNode(prior->ExpectedError(total));
    design.leave_one_out_rms = prior->RmsPerNode(prior->LeaveOneOutError(total));
  }
  // Validation positions: what the fitted set does not see, by the same gain.
  for (int n = 0; n < options.validation; ++n) {
    double gain = 0;
    const std::size_t best = pick_best(&gain);
    objective.Add(candidates[best].elements, +1);
    chosen.push_back(candidates[best]);
    chosen.back().coverage.validation = true;
  }
  // Report in a readable order (fitted by incidence, then validation), with each position's
  // gain given the ones before it.
  std::stable_sort(chosen.begin(), chosen.begin() + options.count,
                   [](const Candidate& a, const Candidate& b) {
                     return a.coverage.theta_in < b.coverage.theta_in;
                   });
  Objective replay(options);
  std::vector<geometry::AxisPositions> fitted;
  Eigen::MatrixXd so_far;
  if (prior) so_far = Eigen::MatrixXd::Zero(prior->components(), prior->components());
  for (const Candidate& c : chosen) {
    DesignedPosition d;
    d.gain = replay.Gain(c.elements);
    replay.Add(c.elements, +1);
    if (prior && !c.coverage.validation) {
      const double before = prior->RmsPerNode(prior->ExpectedError(so_far));
      so_far += c.information;
      d.expected_rms_after = prior->RmsPerNode(prior->ExpectedError(so_far));
      d.prior_gain = before - d.expected_rms_after;
    }
    d.coverage = PositionCoverageAt(rig, c.axes, options.report_grid);
    d.coverage.validation = c.coverage.validation;
    d.reason = Describe(d.coverage, options);
    d.widen = WidenHints(rig, c.axes, options);
    if (!d.coverage.validation) fitted.push_back(c.axes);
    design.positions.push_back(std::move(d));
  }
  design.covered_fraction = ComputeCoverage(rig, fitted, {}, options.report_grid).covered_fraction;
  return design;
}

std::string PlanDesign::ToString() const {
  std::ostringstream out;
  out << "designed plan: " << options.count << " positions"
      << (options.validation ? " + " + std::to_string(options.validation) + " validation" : "")
      << " chosen from " << candidates << " candidates (grid step " << Fixed(step_deg, 1)
      << "°) by "
      << (objective == "prior"
              ? "the expected reconstruction error under the prior '" + prior_name + "'"
              : std::string("weighted (theta_h, theta_d) coverage"))
      << ": coverage score " << Fixed(score, 0) << " of " << Fixed(max_score, 0)
      << ", covered fraction " << Fixed(100 * covered_fraction, 1) << " %\n";
  if (objective == "prior") {
    out << "  RMS error of ln(f cos cos + eps) per table node: " << Fixed(prior_only_rms, 3)
        << " from the prior alone, " << Fixed(expected_rms, 3) << " expected with these photos, "
        << Fixed(leave_one_out_rms, 3)
        << " measured leave-one-material-out over the prior's training materials\n";
  }
  out << "  near retro-reflection: " << (has_retro ? "yes" : "NO (the rig cannot)")
      << "; grazing light: " << (has_grazing ? "yes" : "NO (the rig cannot)") << "\n";
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const DesignedPosition& d = positions[i];
    std::string axes;
    for (const auto& [name, angle] : d.coverage.axes) {
      axes += (axes.empty() ? "" : ", ") + name + " " + Fixed(Degrees(angle), 1);
    }
    out << "  " << i << (d.coverage.validation ? " (validation)" : "") << ": {" << axes
        << "}: " << d.reason << "; coverage gain " << Fixed(d.gain, 0);
    if (objective == "prior" && !d.coverage.validation) {
      out << "; expected error " << Fixed(d.expected_rms_after + d.prior_gain, 3) << " -> "
          << Fixed(d.expected_rms_after, 3);
    }
    out << "\n";
    std::string widen;
    for (const WidenHint& h : d.widen) {
      widen += (widen.empty() ? "" : ", ") + h.change + ": " +
               (h.fits ? std::to_string(h.cells) + " cells" : "corners leave the image");
    }
    out << "     " << d.coverage.cells.size() << " cells; wider coverage with " << widen << "\n";
  }
  return out.str();
}

}  // namespace brdfrig::coverage
