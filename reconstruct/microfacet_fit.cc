#include "reconstruct/microfacet_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "brdf/microfacet_terms.h"
#include "common/angles.h"
#include "common/error.h"
#include "common/format.h"
#include "common/median.h"
#include "reconstruct/energy.h"
#include "reconstruct/log_loss.h"

namespace brdfrig::reconstruct {
namespace {

namespace mf = brdf::microfacet;
constexpr double kMinAlpha = 1e-3, kMaxAlpha = 1.0;
constexpr double kMinF0 = 1e-4, kMinDiffuse = 1e-6;  // kMinDiffuse: starts only
// kDiffuseUnbounded: ln rho_d has an upper bound (0) and no lower one. A material with no
// diffuse term in a channel drives ln rho_d down without end; with a lower bound at ln 1e-6,
// Levenberg–Marquardt reached it and then crawled along it with shrinking steps (Ceres
// projects each step onto the bounds): on the default capture every table fit ran to its
// iteration limit and the GGX starts to 100 iterations, short of their minimum. Unbounded, the
// table fits took 24–82 iterations to lower costs, and four of six GGX starts reached the same
// lowest cost.

// One sample's geometry and data, computed once per fit.
struct Prepared {
  double cos_i, cos_o, cos_h, cos_d, theta_h, theta_d, sqrt_w;
  std::array<double, 3> target;  // ln(eps + f·cos_i)
  std::array<double, 3> f;
};

struct PreparedSet {
  std::vector<Prepared> samples;
  Epsilon eps{};
  double weight_sum = 0;  // after normalization: the number of samples
  double max_theta_h = 0, theta_d_min = 0, theta_d_max = 0;
};

PreparedSet Prepare(const std::vector<DirectionSample>& samples, double epsilon_fraction) {
  PreparedSet set;
  set.eps = LossEpsilon(samples, epsilon_fraction);
  double mean_w = 0;
  int count = 0;
  for (const DirectionSample& s : samples) {
    if (LossWeight(s) > 0) {
      mean_w += LossWeight(s);
      ++count;
    }
  }
  mean_w /= std::max(count, 1);
  set.theta_d_min = 1e9;
  for (const DirectionSample& s : samples) {
    const double w = LossWeight(s);
    if (!(w > 0)) continue;
    Prepared p;
    p.cos_i = s.l.z();
    p.cos_o = s.v.z();
    const brdf::Vec3 h = (s.l + s.v).normalized();
    const HalfAngles a = HalfAnglesOf(s.l, s.v);
    p.cos_h = std::min(1.0, h.z());
    p.cos_d = std::clamp(h.dot(s.l), 0.0, 1.0);
    p.theta_h = a.theta_h;
    p.theta_d = a.theta_d;
    p.sqrt_w = std::sqrt(w / mean_w);
    for (int c = 0; c < 3; ++c) {
      p.f[c] = s.f[c];
      p.target[c] = std::log(set.eps[c] + std::max(s.f[c], 0.0) * p.cos_i);
    }
    set.max_theta_h = std::max(set.max_theta_h, p.theta_h);
    set.theta_d_min = std::min(set.theta_d_min, p.theta_d);
    set.theta_d_max = std::max(set.theta_d_max, p.theta_d);
    set.samples.push_back(p);
  }
  set.weight_sum = static_cast<double>(set.samples.size());
  return set;
}

// ---------------------------------------------------------------- analytic rungs

// Parameters: ln alpha, ln rho_d (R, G, B), ln f0 (R, G, B).
template <brdf::Distribution kDistribution>
struct AnalyticResidual {
  const Prepared* s;
  const Epsilon* eps;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    using std::exp;
    using std::log;
    const T alpha = exp(p[0]);
    T spec;
    if constexpr (kDistribution == brdf::Distribution::kGgx) {
      spec = mf::GgxD(s->cos_h, alpha) * mf::GgxG1(s->cos_i, alpha) * mf::GgxG1(s->cos_o, alpha);
    } else {
      spec = mf::BeckmannD(s->cos_h, alpha) * mf::BeckmannG1(s->cos_i, alpha) *
             mf::BeckmannG1(s->cos_o, alpha);
    }
    spec = spec / (4 * s->cos_i * s->cos_o);
    for (int c = 0; c < 3; ++c) {
      const T f = exp(p[1 + c]) / M_PI + mf::Schlick(exp(p[4 + c]), s->cos_d) * spec;
      r[c] = s->sqrt_w * (log((*eps)[c] + f * s->cos_i) - s->target[c]);
    }
    return true;
  }
};

double SpecularUnit(brdf::Distribution d, const Prepared& s, double alpha) {
  const double g =
      d == brdf::Distribution::kGgx
          ? mf::GgxD(s.cos_h, alpha) * mf::GgxG1(s.cos_i, alpha) * mf::GgxG1(s.cos_o, alpha)
          : mf::BeckmannD(s.cos_h, alpha) * mf::BeckmannG1(s.cos_i, alpha) *
                mf::BeckmannG1(s.cos_o, alpha);
  return g / (4 * s.cos_i * s.cos_o);
}

// rho_d from the darkest tenth of the data (by measure: see WeightedQuantile), times
// `diffuse_scale`; f0 so that the specular term matches where it dominates, for a given alpha.
std::array<double, 7> StartValues(const PreparedSet& set, brdf::Distribution d, double alpha,
                                  double diffuse_scale) {
  std::array<double, 7> x{};
  x[0] = std::log(alpha);
  for (int c = 0; c < 3; ++c) {
    std::vector<std::pair<double, double>> f;
    for (const Prepared& s : set.samples) f.emplace_back(s.f[c], s.sqrt_w * s.sqrt_w);
    const double p10 = WeightedQuantile(std::move(f), 0.1);
    const double rho = std::clamp(M_PI * p10 * diffuse_scale, kMinDiffuse, 0.9);
    std::vector<double> ratios;
    for (const Prepared& s : set.samples) {
      const double spec = s.f[c] - rho / M_PI;
      if (spec > rho / M_PI) ratios.push_back(std::log(spec / SpecularUnit(d, s, alpha)));
    }
    const double f0 = ratios.empty() ? 0.04 : std::clamp(std::exp(Median(ratios)), kMinF0, 1.0);
    x[1 + c] = std::log(rho);
    x[4 + c] = std::log(f0);
  }
  return x;
}

ceres::Solver::Options SolverOptions(int max_iterations) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = max_iterations;
  // The score is a log RMS: relative cost changes below 1e-7 move nothing that matters.
  solver.function_tolerance = 1e-7;
  solver.parameter_tolerance = 1e-8;
  solver.gradient_tolerance = 1e-12;
  solver.num_threads = 1;
  // The fits are bounded, and Ceres then follows every trust-region step with a projected
  // line search that evaluates the Jacobian once more: 30 % of the fit's time, and the
  // trust region alone keeps the bounds (the step is projected onto them either way). 0 turns
  // the line search off (Ceres allows 0 for the trust-region minimizer). Measured on the default
  // capture (bench_reconstruct): the ladder's CPU time −20 %, the chosen rung and its sphere PSNR
  // unchanged, the other rungs' held-out scores within the optimizer's own tolerance.
  solver.max_num_line_search_step_size_iterations = 0;
  return solver;
}

ceres::LossFunction* MakeLoss(double scale) {
  return scale > 0 ? new ceres::HuberLoss(scale) : nullptr;
}

// ---------------------------------------------------------------- table rung

constexpr int kFresnelParams = 4;  // the correction block always has 4 entries (held at 0
                                   // when the fit uses none)
using TableJet = ceres::Jet<double, 15>;

// The table's knot values ln D_k = ln D_0 − Σ_{j<k} exp(s_j) and the drops exp(s_j), worked
// out once per point the solver evaluates instead of once per sample: the sum over the knots
// below a sample's was most of a sample's exponentials. Ceres calls PrepareForEvaluation
// before it evaluates the residuals at a new point. A residual uses the cache only when the
// steps it was computed from are the ones it is handed, and works them out itself otherwise,
// so a stale cache can cost time but never change a result; the sums are the same operations
// in the same order, so the results are identical bit for bit.
class KnotCache : public ceres::EvaluationCallback {
 public:
  KnotCache(const double* head, const double* steps, int knots)
      : head_(head),
        steps_(steps),
        seen_(static_cast<std::size_t>(knots - 1)),
        drops_(seen_.size()),
        log_d_(static_cast<std::size_t>(knots)) {}

  void PrepareForEvaluation(bool /*evaluate_jacobians*/, bool new_evaluation_point) override {
    if (!new_evaluation_point && valid_) return;
    std::copy(steps_, steps_ + seen_.size(), seen_.begin());
    head0_ = head_[0];
    log_d_[0] = head0_;
    for (std::size_t j = 0; j < seen_.size(); ++j) {
      drops_[j] = std::exp(seen_[j]);
      log_d_[j + 1] = log_d_[j] - drops_[j];
    }
    valid_ = true;
  }

  // Whether the cache holds the knots of these parameters, up to step `upto` (exclusive).
  bool Holds(const double* head, const double* steps, int upto) const {
    return valid_ && head[0] == head0_ && std::equal(steps, steps + upto, seen_.begin());
  }
  const double* drops() const { return drops_.data(); }
  double log_d(int k) const { return log_d_[k]; }

 private:
  const double* head_;
  const double* steps_;
  bool valid_ = false;
  double head0_ = 0;
  std::vector<double> seen_, drops_, log_d_;
};

// Head block: ln D_0 (held), ln tail alpha, ln shadowing alpha, ln Z.
// Blocks: head[4], s[knots − 1], ln f0[3], ln rho_d[3], c[4].
class TableResidual : public ceres::CostFunction {
 public:
  TableResidual(const Prepared* s, const Epsilon* eps, int knots, double max_theta_h,
                int fresnel_knots, const KnotCache* cache)
      : s_(s),
        cache_(cache),
        eps_(eps),
        knots_(knots),
        max_theta_h_(max_theta_h),
        fresnel_knots_(fresnel_knots),
        at_(mf::LocateInTable(knots, max_theta_h, s->theta_h)) {
    set_num_residuals(3);
    *mutable_parameter_block_sizes() = {4, knots - 1, 3, 3, kFresnelParams};
  }

  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    const double* head = p[0];
    const double* steps = p[1];
    // The two knots this sample depends on, in double; their derivatives follow below.
    const int upto = at_.tail ? knots_ - 1 : at_.k + 1;  // the knots' steps this sample sees
    double own_drops[256];
    const double* drops = own_drops;
    double lo = head[0], hi = 0;
    if (cache_ && cache_->Holds(head, steps, upto)) {
      drops = cache_->drops();
      lo = cache_->log_d(at_.k);
    } else {
      for (int j = 0; j < upto; ++j) own_drops[j] = std::exp(steps[j]);
      for (int j = 0; j < at_.k; ++j) lo -= drops[j];
    }
    hi = at_.tail ? lo : lo - drops[at_.k];
    // Without Jacobians (the trust region's trial steps) in plain doubles: jets would carry
    // 15 derivatives for nothing.
    if (!jacobians) {
      Residuals<double>(
          p, lo, hi, [](double x, int) { return x; }, residuals);
      return true;
    }
    using J = TableJet;
    J r[3];
    Residuals<J>(
        p, lo, hi, [](double x, int index) { return J(x, index); }, r);
    for (int ch = 0; ch < 3; ++ch) residuals[ch] = r[ch].a;
    for (int ch = 0; ch < 3; ++ch) {
      const auto& g = r[ch].v;
      if (jacobians[0]) {
        double* j = jacobians[0] + ch * 4;
        j[0] = g[0] + g[1];  // every knot moves with ln D_0
        j[1] = g[2];
        j[2] = g[3];
        j[3] = g[4];
      }
      if (jacobians[1]) {
        double* j = jacobians[1] + ch * (knots_ - 1);
        for (int m = 0; m < knots_ - 1; ++m) {
          double coefficient = 0;
          if (m < at_.k) coefficient = g[0] + g[1];
          if (!at_.tail && m == at_.k) coefficient = g[1];
          j[m] = m < upto ? -drops[m] * coefficient : 0;
        }
      }
      if (jacobians[2]) {
        for (int k = 0; k < 3; ++k) jacobians[2][ch * 3 + k] = g[5 + k];
      }
      if (jacobians[3]) {
        for (int k = 0; k < 3; ++k) jacobians[3][ch * 3 + k] = g[8 + k];
      }
      if (jacobians[4]) {
        for (int k = 0; k < kFresnelParams; ++k) {
          jacobians[4][ch * kFresnelParams + k] = g[11 + k];
        }
      }
    }
    return true;
  }

 private:
  // The three channels' residuals in T: `variable(x, i)` makes parameter x of the jet's
  // derivative index i (0, 1: the two knots; 2–4: head; 5–7: ln f0; 8–10: ln rho_d; 11–14: c).
  template <typename T, typename Variable>
  void Residuals(double const* const* p, double lo, double hi, Variable variable, T* r) const {
    using std::exp, std::log;
    const double* head = p[0];
    const T tail_alpha = exp(variable(head[1], 2)), shadow_alpha = exp(variable(head[2], 3)),
            log_z = variable(head[3], 4);
    T c[kFresnelParams];
    for (int k = 0; k < kFresnelParams; ++k) c[k] = variable(p[4][k], 11 + k);
    const T log_d = mf::TableLogDAt(at_, variable(lo, 0), variable(hi, 1), max_theta_h_, tail_alpha,
                                    s_->theta_h);
    const T spec = exp(log_d - log_z) * mf::GgxG1(s_->cos_i, shadow_alpha) *
                   mf::GgxG1(s_->cos_o, shadow_alpha) / (4 * s_->cos_i * s_->cos_o);
    const T correction = exp(mf::FresnelCorrection(c, fresnel_knots_, s_->theta_d));
    for (int ch = 0; ch < 3; ++ch) {
      const T f0 = exp(variable(p[2][ch], 5 + ch)), rho = exp(variable(p[3][ch], 8 + ch));
      const T f = rho / M_PI + mf::Schlick(f0, s_->cos_d) * correction * spec;
      r[ch] = s_->sqrt_w * (log((*eps_)[ch] + f * s_->cos_i) - s_->target[ch]);
    }
  }

  const Prepared* s_;
  const KnotCache* cache_;  // may be null
  const Epsilon* eps_;
  int knots_;
  double max_theta_h_;
  int fresnel_knots_;
  mf::TablePosition at_;
};

template <typename T>
std::vector<T> Knots(const T* head, const T* steps, int knots) {
  using std::exp;
  std::vector<T> log_d(static_cast<std::size_t>(knots));
  log_d[0] = head[0];
  for (int k = 1; k < knots; ++k) log_d[k] = log_d[k - 1] - exp(steps[k - 1]);
  return log_d;
}

// ln Z − ln TableNormalization(knots, tail): the one residual that normalizes D.
struct NormalizationResidual {
  int knots;
  double max_theta_h, weight;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    using std::exp;
    using std::log;
    const std::vector<T> log_d = Knots(p[0], p[1], knots);
    const T z = mf::TableNormalization(log_d.data(), knots, max_theta_h, T(exp(p[0][1])));
    r[0] = weight * (p[0][3] - log(z));
    return true;
  }
};

// The tail's GGX falls over the table's last interval as much as the table does: the tail's
// roughness is fitted from the last knots' slope (C1 in effect), not a constant.
struct TailResidual {
  int knots;
  double max_theta_h, weight;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    using std::exp;
    const double a = mf::TableKnotThetaH(knots - 2, knots, max_theta_h);
    const T alpha = exp(p[0][1]);
    const T table_drop = -exp(p[1][knots - 2]);
    const T tail_drop = mf::LogGgxD(std::cos(max_theta_h), alpha) - mf::LogGgxD(std::cos(a), alpha);
    r[0] = weight * (table_drop - tail_drop);
    return true;
  }
};

// Second differences of ln D at the interior knots: exp(s_{k−1}) − exp(s_k).
struct SmoothnessResidual {
  int knots;
  double weight;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    using std::exp;
    for (int k = 1; k + 1 < knots; ++k) r[k - 1] = weight * (exp(p[0][k - 1]) - exp(p[0][k]));
    return true;
  }
};

struct PullResidual {  // weight · (x − x0) per entry
  std::vector<double> x0;
  double weight;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    for (std::size_t k = 0; k < x0.size(); ++k) r[k] = weight * (p[0][k] - x0[k]);
    return true;
  }
};

struct EntryPullResidual {  // weight · (x[index] − x0)
  int index;
  double x0, weight;
  template <typename T>
  bool operator()(T const* const* p, T* r) const {
    r[0] = weight * (p[0][index] - x0);
    return true;
  }
};

template <typename Functor>
ceres::CostFunction* Dynamic(Functor functor, const std::vector<int>& blocks, int residuals) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<Functor, 8>(new Functor(std::move(functor)));
  for (int b : blocks) cost->AddParameterBlock(b);
  cost->SetNumResiduals(residuals);
  return cost;
}

// ---------------------------------------------------------------- shared

void Finish(const PreparedSet& set, const std::vector<DirectionSample>& samples,
            const MicrofacetFitOptions& options, MicrofacetFit* fit) {
  fit->sample_count = static_cast<int>(set.samples.size());
  fit->max_theta_h = set.max_theta_h;
  fit->theta_d_min = set.theta_d_min;
  fit->theta_d_max = set.theta_d_max;
  nlohmann::json& d = fit->diagnostics;
  if (options.energy_check) {
    std::string note;
    fit->energy_scale = LimitMicrofacetEnergy(&fit->params, &note);
    if (!note.empty()) fit->warnings.push_back(note);
  }
  const brdf::MicrofacetModel model(fit->params);
  fit->residual = LogLossRms(model, samples, set.eps);
  // Where the diffuse term carries at least half of the model's value, the data see it.
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  std::array<int, 3> dominated{};
  for (const DirectionSample& s : samples) {
    const brdf::Rgb f = model.Eval(s.l, s.v, n);
    for (int c = 0; c < 3; ++c) {
      if (fit->params.diffuse[c] / M_PI >= 0.5 * f[c]) ++dominated[c];
    }
  }
  static constexpr const char* kChannel[3] = {"red", "green", "blue"};
  for (int c = 0; c < 3; ++c) {
    fit->diffuse_observed[c] = dominated[c] >= 10;
    if (!fit->diffuse_observed[c]) {
      fit->warnings.push_back(std::string("diffuse unobserved (") + kChannel[c] +
                              "): the specular lobe outshines it in every sample (theta_h up "
                              "to " +
                              Fixed(Degrees(set.max_theta_h), 1) +
                              "°), so rho_d is an upper bound at best; an off-specular photo "
                              "would measure it");
    }
  }
  d["residual"] = fit->residual;
  d["sample_count"] = fit->sample_count;
  d["max_theta_h_deg"] = Degrees(set.max_theta_h);
  d["theta_d_range_deg"] = {Degrees(set.theta_d_min), Degrees(set.theta_d_max)};
  d["diffuse_observed"] = fit->diffuse_observed;
  d["epsilon"] = set.eps;
  d["energy_scale"] = fit->energy_scale;
  if (options.albedo_diagnostic) d["albedo_max"] = MaxAlbedo(model).albedo;
}

void RequireSamples(const PreparedSet& set) {
  if (set.samples.size() < 16) {
    throw Error("microfacet fit: only " + std::to_string(set.samples.size()) +
                " usable direction samples");
  }
}

}  // namespace

void MicrofacetFitOptions::Validate() const {
  if (table_knots < 4 || table_knots > 256) {
    throw OptionsError("MicrofacetFitOptions.table_knots = " + std::to_string(table_knots) +
                       "; must be in [4, 256]");
  }
  if (fresnel_knots != 0 && (fresnel_knots < 2 || fresnel_knots > kFresnelParams)) {
    throw OptionsError("MicrofacetFitOptions.fresnel_knots = " + std::to_string(fresnel_knots) +
                       "; must be 0 or in [2, 4]");
  }
  if (!(fresnel_prior > 0)) throw OptionsError("MicrofacetFitOptions.fresnel_prior must be > 0");
  if (!(smoothness >= 0)) throw OptionsError("MicrofacetFitOptions.smoothness must be >= 0");
  if (!(epsilon_fraction > 0)) {
    throw OptionsError("MicrofacetFitOptions.epsilon_fraction must be > 0");
  }
  if (!(loss_scale >= 0)) throw OptionsError("MicrofacetFitOptions.loss_scale must be >= 0");
  if (max_iterations < 1) throw OptionsError("MicrofacetFitOptions.max_iterations must be >= 1");
}

MicrofacetFit FitAnalyticMicrofacet(const std::vector<DirectionSample>& samples,
                                    brdf::Distribution distribution,
                                    const MicrofacetFitOptions& options,
                                    const brdf::MicrofacetModelParams* start) {
  options.Validate();
  if (distribution == brdf::Distribution::kTable) {
    throw Error("FitAnalyticMicrofacet: the table rung has its own fit");
  }
  const auto start_time = std::chrono::steady_clock::now();
  const PreparedSet set = Prepare(samples, options.epsilon_fraction);
  RequireSamples(set);
  // A few starting roughnesses and diffuse levels: the log loss has local minima between a
  // sharp lobe that fits the peak and a wide one that fits the flanks, and between a diffuse
  // level that carries the flanks and one under them.
  static constexpr double kStartAlphas[3] = {0.03, 0.1, 0.3};
  static constexpr double kStartDiffuseScales[2] = {1.0, 0.2};
  constexpr int kStarts = 6;
  std::array<std::array<double, 7>, kStarts> starts{};
  double* best = nullptr;
  double best_cost = std::numeric_limits<double>::infinity();
  std::unique_ptr<ceres::Problem> best_problem;
  for (int i = 0; i < (start ? 1 : kStarts); ++i) {
    std::array<double, 7>& x = starts[i];
    x = StartValues(set, distribution, kStartAlphas[i % 3], kStartDiffuseScales[i / 3]);
    if (start) {
      x[0] = std::log(std::clamp(start->alpha, kMinAlpha, kMaxAlpha));
      for (int c = 0; c < 3; ++c) {
        x[1 + c] = std::log(std::clamp(start->diffuse[c], kMinDiffuse, 1.0));
        x[4 + c] = std::log(std::clamp(start->f0[c], kMinF0, 1.0));
      }
    }
    ceres::Problem::Options problem_options;
    auto problem = std::make_unique<ceres::Problem>(problem_options);
    for (const Prepared& s : set.samples) {
      ceres::CostFunction* cost =
          distribution == brdf::Distribution::kGgx
              ? static_cast<ceres::CostFunction*>(
                    new ceres::AutoDiffCostFunction<AnalyticResidual<brdf::Distribution::kGgx>, 3,
                                                    7>(
                        new AnalyticResidual<brdf::Distribution::kGgx>{&s, &set.eps}))
              : new ceres::AutoDiffCostFunction<AnalyticResidual<brdf::Distribution::kBeckmann>, 3,
                                                7>(
                    new AnalyticResidual<brdf::Distribution::kBeckmann>{&s, &set.eps});
      problem->AddResidualBlock(cost, MakeLoss(options.loss_scale), x.data());
    }
    problem->SetParameterLowerBound(x.data(), 0, std::log(kMinAlpha));
    problem->SetParameterUpperBound(x.data(), 0, std::log(kMaxAlpha));
    for (int c = 0; c < 3; ++c) {
      problem->SetParameterUpperBound(x.data(), 1 + c, 0);  // ln rho_d: kDiffuseUnbounded
      problem->SetParameterLowerBound(x.data(), 4 + c, std::log(kMinF0));
      problem->SetParameterUpperBound(x.data(), 4 + c, 0);
    }
    ceres::Solver::Summary summary;
    ceres::Solve(SolverOptions(options.max_iterations), problem.get(), &summary);
    if (summary.final_cost < best_cost) {
      best_cost = summary.final_cost;
      best = x.data();
      best_problem = std::move(problem);
    }
  }
  MicrofacetFit fit;
  fit.params.distribution = distribution;
  fit.params.alpha = std::exp(best[0]);
  for (int c = 0; c < 3; ++c) {
    fit.params.diffuse[c] = std::min(1.0, std::exp(best[1 + c]));
    fit.params.f0[c] = std::min(1.0, std::exp(best[4 + c]));
  }
  if (fit.params.alpha <= 1.01 * kMinAlpha) {
    fit.warnings.push_back("alpha at its lower bound " + Fixed(kMinAlpha, 3) +
                           ": the lobe is sharper than the data resolve");
  }
  if (options.covariance && best_problem) {
    // Covariance of the internal (log) parameters, scaled by the residual variance; reported
    // as relative std-devs of alpha, rho_d and f0 (d x / x = d ln x).
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.null_space_rank = -1;
    ceres::Covariance covariance(co);
    const std::vector<std::pair<const double*, const double*>> block = {{best, best}};
    if (covariance.Compute(block, best_problem.get())) {
      double cov[49];
      covariance.GetCovarianceBlock(best, best, cov);
      const double dof = std::max(1.0, 3.0 * static_cast<double>(set.samples.size()) - 7);
      const double variance = 2 * best_cost / dof;
      std::vector<double> rel;
      for (int i = 0; i < 7; ++i) rel.push_back(std::sqrt(std::max(0.0, cov[i * 8] * variance)));
      fit.diagnostics["relative_stddev"] = {{"alpha", rel[0]},
                                            {"diffuse", {rel[1], rel[2], rel[3]}},
                                            {"f0", {rel[4], rel[5], rel[6]}}};
    }
  }
  Finish(set, samples, options, &fit);
  fit.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return fit;
}

MicrofacetFit FitTableMicrofacet(const std::vector<DirectionSample>& samples,
                                 const brdf::MicrofacetModelParams& start,
                                 const MicrofacetFitOptions& options) {
  options.Validate();
  const auto start_time = std::chrono::steady_clock::now();
  const PreparedSet set = Prepare(samples, options.epsilon_fraction);
  RequireSamples(set);
  const int knots = options.table_knots;
  const double max_theta_h = std::clamp(set.max_theta_h, 1e-3, M_PI / 2);
  const double start_alpha = std::clamp(start.alpha, kMinAlpha, kMaxAlpha);

  // Start: the GGX fit's D at the knots (monotone for alpha <= 1), its f0 and rho_d.
  std::array<double, 4> head = {mf::LogGgxD(1.0, start_alpha), std::log(start_alpha),
                                std::log(start_alpha), 0};
  std::vector<double> steps(static_cast<std::size_t>(knots - 1));
  for (int k = 0; k + 1 < knots; ++k) {
    const double drop =
        mf::LogGgxD(std::cos(mf::TableKnotThetaH(k, knots, max_theta_h)), start_alpha) -
        mf::LogGgxD(std::cos(mf::TableKnotThetaH(k + 1, knots, max_theta_h)), start_alpha);
    steps[k] = std::log(std::max(drop, 1e-6));
  }
  {
    const std::vector<double> log_d = Knots(head.data(), steps.data(), knots);
    head[3] = std::log(mf::TableNormalization(log_d.data(), knots, max_theta_h, start_alpha));
  }
  std::array<double, 3> log_f0{}, log_rho{};
  for (int c = 0; c < 3; ++c) {
    log_f0[c] = std::log(std::clamp(start.f0[c], kMinF0, 1.0));
    log_rho[c] = std::log(std::clamp(start.diffuse[c], kMinDiffuse, 1.0));
  }
  std::array<double, kFresnelParams> fresnel{};

  KnotCache knot_cache(head.data(), steps.data(), knots);
  ceres::Problem::Options problem_options;
  problem_options.evaluation_callback = &knot_cache;
  ceres::Problem problem(problem_options);
  for (const Prepared& s : set.samples) {
    problem.AddResidualBlock(
        new TableResidual(&s, &set.eps, knots, max_theta_h, options.fresnel_knots, &knot_cache),
        MakeLoss(options.loss_scale), head.data(), steps.data(), log_f0.data(), log_rho.data(),
        fresnel.data());
  }
  const double n = set.weight_sum;
  // Priors scale with the data so that their strength does not depend on the sample count.
  const double per_knot = std::sqrt(n / knots);
  problem.AddResidualBlock(
      Dynamic(NormalizationResidual{knots, max_theta_h, std::sqrt(n)}, {4, knots - 1}, 1), nullptr,
      head.data(), steps.data());
  problem.AddResidualBlock(Dynamic(TailResidual{knots, max_theta_h, per_knot}, {4, knots - 1}, 1),
                           nullptr, head.data(), steps.data());
  if (options.smoothness > 0) {
    problem.AddResidualBlock(
        Dynamic(SmoothnessResidual{knots, options.smoothness * per_knot}, {knots - 1}, knots - 2),
        nullptr, steps.data());
  }
  const double fresnel_weight = options.fresnel_prior * std::sqrt(n / kFresnelParams);
  problem.AddResidualBlock(
      Dynamic(PullResidual{std::vector<double>(kFresnelParams, 0.0), fresnel_weight},
              {kFresnelParams}, kFresnelParams),
      nullptr, fresnel.data());
  // Smith's G is seen only towards grazing angles: held weakly to the GGX fit's roughness.
  problem.AddResidualBlock(
      Dynamic(EntryPullResidual{2, std::log(start_alpha), fresnel_weight}, {4}, 1), nullptr,
      head.data());
  problem.SetManifold(head.data(), new ceres::SubsetManifold(4, {0}));
  for (int i : {1, 2}) {
    problem.SetParameterLowerBound(head.data(), i, std::log(kMinAlpha));
    problem.SetParameterUpperBound(head.data(), i, std::log(2.0));
  }
  for (int k = 0; k + 1 < knots; ++k) {
    problem.SetParameterLowerBound(steps.data(), k, std::log(1e-9));
    problem.SetParameterUpperBound(steps.data(), k, std::log(50.0));
  }
  for (int c = 0; c < 3; ++c) {
    problem.SetParameterLowerBound(log_f0.data(), c, std::log(kMinF0));
    problem.SetParameterUpperBound(log_f0.data(), c, 0);
    problem.SetParameterUpperBound(log_rho.data(), c, 0);  // kDiffuseUnbounded
  }
  for (int k = 0; k < kFresnelParams; ++k) {
    problem.SetParameterLowerBound(fresnel.data(), k, -5);
    problem.SetParameterUpperBound(fresnel.data(), k, 5);
  }
  if (options.fresnel_knots == 0) problem.SetParameterBlockConstant(fresnel.data());
  ceres::Solver::Summary summary;
  ceres::Solve(SolverOptions(options.max_iterations), &problem, &summary);

  MicrofacetFit fit;
  brdf::MicrofacetModelParams& p = fit.params;
  p.distribution = brdf::Distribution::kTable;
  p.log_d = Knots(head.data(), steps.data(), knots);
  p.max_theta_h = max_theta_h;
  p.alpha = std::exp(head[1]);
  p.shadowing_alpha = std::exp(head[2]);
  for (int c = 0; c < 3; ++c) {
    p.f0[c] = std::min(1.0, std::exp(log_f0[c]));
    p.diffuse[c] = std::min(1.0, std::exp(log_rho[c]));
  }
  // The model normalizes D itself; f0 then means what it says only if the fit's ln Z is the
  // table's integral (the normalization residual makes it so to ~1e-6).
  const double z = mf::TableNormalization(p.log_d.data(), knots, max_theta_h, p.alpha);
  const double z_mismatch = std::log(z) - head[3];
  if (options.fresnel_knots > 0) {
    p.fresnel_knots.assign(fresnel.begin(), fresnel.begin() + options.fresnel_knots);
    // Knots whose support holds no observed theta_d are the prior's value, not the data's.
    const double spacing = (M_PI / 2) / (options.fresnel_knots - 1);
    std::vector<double> prior_only;
    for (int k = 0; k < options.fresnel_knots; ++k) {
      const double at = k * spacing;
      if (at + spacing <= set.theta_d_min || at - spacing >= set.theta_d_max) {
        prior_only.push_back(Degrees(at));
      }
    }
    fit.diagnostics["fresnel_knots_prior_only_deg"] = prior_only;
    if (!prior_only.empty()) {
      std::string list;
      for (double d : prior_only) list += (list.empty() ? "" : ", ") + Fixed(d, 0) + "°";
      fit.warnings.push_back("Fresnel correction knots at theta_d " + list +
                             " are outside the observed theta_d range (" +
                             Fixed(Degrees(set.theta_d_min), 1) + "°–" +
                             Fixed(Degrees(set.theta_d_max), 1) + "°): prior only (0)");
    }
  }
  fit.warnings.push_back("D beyond theta_h " + Fixed(Degrees(max_theta_h), 1) +
                         "° (the largest observed) is the fitted GGX tail, alpha " +
                         Fixed(p.alpha, 4));
  fit.diagnostics["tail_alpha"] = p.alpha;
  fit.diagnostics["shadowing_alpha"] = p.shadowing_alpha;
  fit.diagnostics["normalization_mismatch"] = z_mismatch;
  fit.diagnostics["iterations"] = summary.iterations.size();
  Finish(set, samples, options, &fit);
  fit.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return fit;
}

}  // namespace brdfrig::reconstruct
