#include "reconstruct/slice_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "brdf/logistic.h"
#include "common/angles.h"
#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::reconstruct {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One sample's residual sqrt(w)·(ln m(theta) − ln f) with its analytic derivative with respect to
// the internal parameters (a, b, s, x0).
class LogLobeResidual : public ceres::SizedCostFunction<1, 4> {
 public:
  LogLobeResidual(double theta, double log_f, double sqrt_w)
      : theta_(theta), log_f_(log_f), sqrt_w_(sqrt_w) {}

  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const double* p = parameters[0];
    const double a2 = std::exp(p[0]), d = std::exp(p[1]), h = std::exp(p[2]), x0 = p[3];
    const double z = (theta_ - x0) / h;
    const double sigma = brdf::Logistic(-z);
    const double m = a2 + d * sigma;
    if (!(m > 0) || !std::isfinite(m)) return false;
    residual[0] = sqrt_w_ * (std::log(m) - log_f_);
    if (jacobians && jacobians[0]) {
      const double slope = d * sigma * (1 - sigma);  // −dm/dz
      const double scale = sqrt_w_ / m;
      jacobians[0][0] = scale * a2;
      jacobians[0][1] = scale * d * sigma;
      jacobians[0][2] = scale * slope * z;
      jacobians[0][3] = scale * slope / h;
    }
    return true;
  }

 private:
  double theta_, log_f_, sqrt_w_;
};

struct ChannelData {
  std::vector<double> theta, log_f, weight;
};

// A median profile of f over theta in a few bins: start values and identifiability checks
// without trusting single noisy pixels.
struct Profile {
  std::vector<double> theta, f;
};

Profile MedianProfile(const std::vector<double>& theta, const std::vector<double>& f, int bins) {
  std::vector<std::size_t> order(theta.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto i, auto j) { return theta[i] < theta[j]; });
  Profile profile;
  const std::size_t per_bin =
      std::max<std::size_t>(1, order.size() / static_cast<std::size_t>(bins));
  for (std::size_t start = 0; start < order.size(); start += per_bin) {
    const std::size_t end = std::min(order.size(), start + per_bin);
    std::vector<double> values;
    double theta_sum = 0;
    for (std::size_t k = start; k < end; ++k) {
      values.push_back(f[order[k]]);
      theta_sum += theta[order[k]];
    }
    std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2),
                     values.end());
    profile.theta.push_back(theta_sum / static_cast<double>(end - start));
    profile.f.push_back(values[values.size() / 2]);
  }
  return profile;
}

// Theta where the (decreasing) profile first falls below `level`, linearly interpolated.
double Crossing(const Profile& p, double level) {
  for (std::size_t i = 1; i < p.f.size(); ++i) {
    if (p.f[i - 1] >= level && p.f[i] < level) {
      const double t = (p.f[i - 1] - level) / std::max(p.f[i - 1] - p.f[i], 1e-300);
      return p.theta[i - 1] + t * (p.theta[i] - p.theta[i - 1]);
    }
  }
  return kNaN;
}

}  // namespace

void SliceFitOptions::Validate() const {
  CheckOption(max_iterations >= 1, "SliceFitOptions.max_iterations", max_iterations, ">= 1");
  CheckOption(function_tolerance > 0, "SliceFitOptions.function_tolerance", function_tolerance,
              "> 0");
  CheckOption(parameter_tolerance > 0, "SliceFitOptions.parameter_tolerance", parameter_tolerance,
              "> 0");
  CheckOption(loss_scale >= 0, "SliceFitOptions.loss_scale", loss_scale, ">= 0");
}

SliceFit FitSlice(const BrdfSamples& samples, const SliceFitOptions& options,
                  const std::optional<std::array<double, 3>>& fixed_a2) {
  options.Validate();
  SliceFit fit;
  fit.slice.theta_in = samples.theta_in;
  fit.theta_min = samples.ThetaMin();
  fit.theta_max = samples.ThetaMax();
  // A lobe edge sharper than the spacing of the data cannot be measured; h stays above a
  // fraction of it so the optimizer does not chase h → 0.
  const double min_h = std::max(1e-5, 0.25 * samples.angular_pixel_size);

  std::array<brdf::LobeParams, 3> start{};
  std::array<ChannelData, 3> data;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> f;
    for (std::size_t i = 0; i < samples.theta.size(); ++i) {
      const double value = samples.f[i][c];
      if (value > 0 && std::isfinite(value) && std::isfinite(samples.theta[i])) {
        data[c].theta.push_back(samples.theta[i]);
        data[c].log_f.push_back(std::log(value));
        data[c].weight.push_back(samples.weight[i]);
        f.push_back(value);
      }
    }
    if (data[c].theta.size() < 8) {
      throw Error("slice at theta_in " + std::to_string(Degrees(samples.theta_in)) + "°: only " +
                  std::to_string(data[c].theta.size()) +
                  " usable samples in a channel (all clipped, dark or outside the cut-out?)");
    }
    fit.sample_count = std::max(fit.sample_count, static_cast<int>(data[c].theta.size()));
    const Profile profile = MedianProfile(data[c].theta, f, 64);
    const double top = *std::max_element(profile.f.begin(), profile.f.end());
    const double bottom = *std::min_element(profile.f.begin(), profile.f.end());
    brdf::LobeParams& p = start[c];
    p.a1 = top;
    p.a2 = fixed_a2 ? (*fixed_a2)[c] : bottom;
    const double x_mid = Crossing(profile, 0.5 * (top + bottom));
    const double x_hi = Crossing(profile, bottom + 0.75 * (top - bottom));
    const double x_lo = Crossing(profile, bottom + 0.25 * (top - bottom));
    const double span = profile.theta.back() - profile.theta.front();
    p.x0 = std::isfinite(x_mid) ? x_mid : profile.theta.front() + 0.5 * span;
    p.h = std::isfinite(x_hi) && std::isfinite(x_lo) && x_lo > x_hi ? (x_lo - x_hi) / 2.197
                                                                    : std::max(span / 8, min_h);
    p.h = std::max(p.h, min_h);
  }

  for (int c = 0; c < 3; ++c) {
    const brdf::LobeParams& p0 = start[c];
    const double a2 = std::max(p0.a2, 1e-9 * std::max(p0.a1, 1e-30));
    std::array<double, 4> x = {std::log(a2), std::log(std::max(p0.a1 - a2, 1e-3 * a2)),
                               std::log(p0.h), p0.x0};
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    ceres::CauchyLoss loss(options.loss_scale > 0 ? options.loss_scale : 1.0);
    for (std::size_t i = 0; i < data[c].theta.size(); ++i) {
      problem.AddResidualBlock(
          new LogLobeResidual(data[c].theta[i], data[c].log_f[i], std::sqrt(data[c].weight[i])),
          options.loss_scale > 0 ? &loss : nullptr, x.data());
    }
    problem.SetParameterLowerBound(x.data(), 2, std::log(min_h));
    problem.SetParameterUpperBound(x.data(), 2, std::log(M_PI));
    if (fixed_a2) {
      problem.SetManifold(x.data(), new ceres::SubsetManifold(4, {0}));
    }
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = options.function_tolerance;
    solver.parameter_tolerance = options.parameter_tolerance;
    solver.gradient_tolerance = 1e-14;
    solver.num_threads = 1;
    // No projected line search after each trust-region step (bounded problem: h): it evaluates
    // the Jacobian once more per step; see SolverOptions in microfacet_fit.cc.
    solver.max_num_line_search_step_size_iterations = 0;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);

    ChannelFit& out = fit.channel[c];
    out.iterations = static_cast<int>(summary.iterations.size());
    const double a2_fit = std::exp(x[0]), d_fit = std::exp(x[1]), h_fit = std::exp(x[2]);
    out.params = {a2_fit + d_fit, a2_fit, h_fit, x[3]};
    double weight_sum = 0, sq = 0;
    for (std::size_t i = 0; i < data[c].theta.size(); ++i) {
      const double r = std::log(brdf::EvalLobe(out.params, data[c].theta[i])) - data[c].log_f[i];
      sq += data[c].weight[i] * r * r;
      weight_sum += data[c].weight[i];
    }
    out.rms_log_residual = std::sqrt(sq / std::max(weight_sum, 1e-300));
    out.stddev.fill(kNaN);
    if (options.covariance && data[c].theta.size() > 4) {
      ceres::Covariance::Options covariance_options;
      covariance_options.algorithm_type = ceres::DENSE_SVD;
      covariance_options.null_space_rank = -1;
      ceres::Covariance covariance(covariance_options);
      std::vector<std::pair<const double*, const double*>> blocks = {{x.data(), x.data()}};
      if (covariance.Compute(blocks, &problem)) {
        double cov[16];
        covariance.GetCovarianceBlock(x.data(), x.data(), cov);
        // Residuals are not unit-variance: scale by the fit's residual variance.
        const double dof = std::max(1.0, static_cast<double>(data[c].theta.size()) - 4);
        const double variance = 2 * summary.final_cost / dof;
        // d(A1, A2, h, x0) / d(a, b, s, x0).
        const double t[4][4] = {
            {a2_fit, d_fit, 0, 0}, {a2_fit, 0, 0, 0}, {0, 0, h_fit, 0}, {0, 0, 0, 1}};
        for (int i = 0; i < 4; ++i) {
          double v = 0;
          for (int j = 0; j < 4; ++j) {
            for (int k = 0; k < 4; ++k) v += t[i][j] * cov[j * 4 + k] * t[i][k];
          }
          out.stddev[i] = v >= 0 ? std::sqrt(v * variance) : kNaN;
        }
      }
    }
    fit.slice.channel[c] = out.params;
  }

  // What the data support, judged on the green channel's lobe (the brightest in most scenes)
  // but flagged if any channel shows it.
  for (int c = 0; c < 3; ++c) {
    const brdf::LobeParams& p = fit.channel[c].params;
    const double contrast = (p.a1 - p.a2) / std::max(p.a2, 1e-300);
    if (contrast < 0.05) fit.flat = true;
    if (fit.theta_max < p.x0 + 3 * p.h) fit.a2_observed = false;
    // The peak side of the lobe is unsampled (clipped or outside the cut-out).
    if (fit.theta_min > p.x0 - p.h) fit.a1_observed = false;
    if (p.h <= 1.01 * min_h) fit.h_resolved = false;
  }
  if (fit.flat) {
    // A flat slice: the lobe's position and width mean nothing; make them canonical so that the
    // file does not carry noise.
    for (int c = 0; c < 3; ++c) {
      ChannelFit& ch = fit.channel[c];
      const double mean =
          std::exp(std::accumulate(data[c].log_f.begin(), data[c].log_f.end(), 0.0) /
                   static_cast<double>(data[c].log_f.size()));
      ch.params = {mean, mean, 1.0, 0.0};
      ch.stddev[2] = ch.stddev[3] = kNaN;
      fit.slice.channel[c] = ch.params;
    }
    fit.a2_observed = fit.a1_observed = fit.h_resolved = true;
    fit.warnings.push_back(
        "no lobe (peak within 5% of the floor): a flat, Lambertian-like slice; "
        "x0 and h are undetermined and set to 0 and 1");
  }
  if (!fit.a2_observed) {
    fit.warnings.push_back("A2 unobserved: samples reach theta " +
                           std::to_string(Degrees(fit.theta_max)) + "°, short of the lobe's tail");
  }
  if (!fit.a1_observed) {
    fit.warnings.push_back(
        "A1 unobserved: no samples near the mirror direction (nearest at theta " +
        std::to_string(Degrees(fit.theta_min)) + "°)");
  }
  if (!fit.h_resolved) {
    fit.warnings.push_back(
        "h unresolved: the lobe's edge is sharper than the angular resolution (" +
        std::to_string(Degrees(samples.angular_pixel_size)) + "° per pixel); h is an upper bound");
  }
  return fit;
}

}  // namespace brdfrig::reconstruct
