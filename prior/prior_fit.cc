#include "prior/prior_fit.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::prior {

void PriorFitOptions::Validate() const {
  CheckOption(misfit_limit > 0 && std::isfinite(misfit_limit), "PriorFitOptions.misfit_limit",
              misfit_limit, "positive");
  CheckOption(bandwidth >= 0 && bandwidth < 100, "PriorFitOptions.bandwidth", bandwidth,
              "in [0, 100)");
  CheckOption(correction_reach >= 0 && correction_reach <= 8, "PriorFitOptions.correction_reach",
              correction_reach, "in [0, 8]");
}

namespace {

// The samples of one kind (values or bounds) in the prior's terms: each one's mean μ and
// components b interpolated at its coordinates, its weight, and its q per channel.
struct Rows {
  std::vector<brdf::Stencil> stencils;
  Eigen::MatrixXd b;
  Eigen::VectorXd mu, w;
  std::array<Eigen::VectorXd, 3> q;
  Eigen::Index Size() const { return mu.size(); }
};

Rows RowsOf(const MeasuredPrior& prior, const std::vector<Observation>& observations,
            bool upper_bounds) {
  const brdf::RusinkiewiczGrid& grid = prior.grid;
  Rows rows;
  std::vector<double> weights;
  std::array<std::vector<double>, 3> q;
  for (const Observation& o : observations) {
    if (o.upper_bound != upper_bounds) continue;
    if (!(o.weight > 0) || o.l.z() <= 0 || o.v.z() <= 0 || !o.f.isFinite().all()) continue;
    rows.stencils.push_back(brdf::StencilAt(grid, brdf::ToHalfDiffAngles(o.l, o.v)));
    weights.push_back(o.weight);
    const double c = brdf::CosineProduct(grid, o.l, o.v);
    for (int ch = 0; ch < 3; ++ch) q[ch].push_back(brdf::MapValue(grid, o.f[ch], c));
  }
  const auto n = static_cast<Eigen::Index>(rows.stencils.size());
  rows.b.resize(n, prior.Components());
  rows.mu.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    rows.b.row(i).setZero();
    rows.mu[i] = 0;
    for (int j = 0; j < 8; ++j) {
      const double w = rows.stencils[i].weight[j];
      if (w == 0) continue;
      rows.b.row(i) += w * prior.components.row(rows.stencils[i].node[j]);
      rows.mu[i] += w * prior.mean[rows.stencils[i].node[j]];
    }
  }
  rows.w = Eigen::Map<const Eigen::VectorXd>(weights.data(), n);
  for (int ch = 0; ch < 3; ++ch) rows.q[ch] = Eigen::Map<const Eigen::VectorXd>(q[ch].data(), n);
  return rows;
}

// Step 1 for one channel with the bounds the fit exceeds added as values, until that set
// stops changing (a semismooth Newton method on the one-sided penalty: a few rounds; capped,
// the last round's coefficients stand). Returns the coefficients; *active counts the bounds.
Eigen::VectorXd SolveChannel(const Eigen::MatrixXd& normal, const Eigen::VectorXd& rhs,
                             const Rows& bounds, int ch, double inv_s2, int* active) {
  Eigen::VectorXd c = normal.ldlt().solve(rhs);
  std::vector<bool> in(static_cast<std::size_t>(bounds.Size()), false);
  for (int round = 0; round < 20; ++round) {
    const Eigen::VectorXd fitted = bounds.mu + bounds.b * c;
    bool changed = false;
    for (Eigen::Index i = 0; i < bounds.Size(); ++i) {
      const bool above = fitted[i] > bounds.q[ch][i];
      changed = changed || above != in[static_cast<std::size_t>(i)];
      in[static_cast<std::size_t>(i)] = above;
    }
    if (!changed) break;
    Eigen::MatrixXd n = normal;
    Eigen::VectorXd r = rhs;
    for (Eigen::Index i = 0; i < bounds.Size(); ++i) {
      if (!in[static_cast<std::size_t>(i)]) continue;
      const double w = bounds.w[i] * inv_s2;
      n.selfadjointView<Eigen::Lower>().rankUpdate(bounds.b.row(i).transpose(), w);
      r += bounds.b.row(i).transpose() * (w * (bounds.q[ch][i] - bounds.mu[i]));
    }
    c = n.ldlt().solve(r);  // LDLT reads the lower triangle only
  }
  *active = static_cast<int>(std::count(in.begin(), in.end(), true));
  return c;
}

// The Gaussian prior of one channel's coefficients: precision and mean.
struct ChannelPrior {
  Eigen::MatrixXd precision;
  Eigen::VectorXd mean;
  Eigen::VectorXd weights;  // of the training channels (empty for the global Gaussian)
};

// With bandwidth h = 0, the training channels' Gaussian: mean 0, variances s². With h > 0, the
// prior local to the training channels this channel's data resemble: each training channel's
// coefficients c_j the centre of a Gaussian of covariance h²·diag(s²), weighted by its evidence
// under the fit's own likelihood (data_normal, data_rhs: the data's normal matrix and
// right-hand side), the mixture replaced by its moment-matched Gaussian (mean Σ π_j c_j,
// covariance h²·diag(s²) + Σ π_j (c_j − m)(c_j − m)ᵀ). Real materials cluster (metals,
// plastics, fabrics): what a material does where no photo looked is better told by the
// materials it resembles where photos did look than by all of them (docs/prior.md).
ChannelPrior PriorOf(const MeasuredPrior& prior, double h, const Eigen::MatrixXd& data_normal,
                     const Eigen::VectorXd& data_rhs) {
  const Eigen::Index k = prior.variances.size();
  if (h <= 0) {
    return {prior.variances.cwiseInverse().asDiagonal(), Eigen::VectorXd::Zero(k), {}};
  }
  const Eigen::MatrixXd& centres = prior.training_coefficients;
  const Eigen::VectorXd lambda = prior.variances.cwiseInverse() / (h * h);
  Eigen::MatrixXd normal = data_normal;
  normal.diagonal() += lambda;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
  // log p(data | centre j) up to terms shared by every j.
  Eigen::VectorXd log_evidence(centres.rows());
  for (Eigen::Index j = 0; j < centres.rows(); ++j) {
    const Eigen::VectorXd c = centres.row(j).transpose();
    const Eigen::VectorXd eta = data_rhs + lambda.cwiseProduct(c);
    log_evidence[j] = 0.5 * (eta.dot(ldlt.solve(eta)) - c.dot(lambda.cwiseProduct(c)));
  }
  Eigen::VectorXd weights = (log_evidence.array() - log_evidence.maxCoeff()).exp().matrix();
  weights /= weights.sum();
  ChannelPrior p;
  p.mean = centres.transpose() * weights;
  const Eigen::MatrixXd spread = centres.rowwise() - p.mean.transpose();
  Eigen::MatrixXd covariance = spread.transpose() * weights.asDiagonal() * spread;
  covariance.diagonal() += prior.variances * (h * h);
  p.precision = covariance.ldlt().solve(Eigen::MatrixXd::Identity(k, k));
  p.weights = weights;
  return p;
}

// Spreads per-node sums over their neighbours: a separable Gaussian of standard deviation
// `reach` node steps along θh, θd and φd (cut at 3 reach, the grid's edges not wrapped).
void SpreadOverNodes(const brdf::RusinkiewiczGrid& grid, double reach, std::vector<double>* v) {
  if (reach <= 0) return;
  const int radius = static_cast<int>(std::ceil(3 * reach));
  std::vector<double> kernel(2 * radius + 1);
  for (int d = -radius; d <= radius; ++d)
    kernel[d + radius] = std::exp(-0.5 * d * d / (reach * reach));
  const int n[3] = {grid.theta_h, grid.theta_d, grid.phi_d};
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> out(v->size(), 0.0);
    for (int ih = 0; ih < grid.theta_h; ++ih) {
      for (int id = 0; id < grid.theta_d; ++id) {
        for (int ip = 0; ip < grid.phi_d; ++ip) {
          const double x = (*v)[grid.Index(ih, id, ip)];
          if (x == 0) continue;
          int at[3] = {ih, id, ip};
          const int centre = at[axis];
          for (int d = -radius; d <= radius; ++d) {
            at[axis] = centre + d;
            if (at[axis] < 0 || at[axis] >= n[axis]) continue;
            out[grid.Index(at[0], at[1], at[2])] += kernel[d + radius] * x;
          }
        }
      }
    }
    *v = std::move(out);
  }
}

// Step 2's move of every node: the weighted mean of the residuals of the samples around it
// (their stencils, spread over `reach` node steps), shrunk by the correction weight.
std::vector<double> CorrectionOf(const brdf::RusinkiewiczGrid& grid, const Rows& values,
                                 const Eigen::VectorXd& residual, double reach, double weight) {
  std::vector<double> num(grid.Cells(), 0.0), den(grid.Cells(), 0.0);
  for (Eigen::Index i = 0; i < values.Size(); ++i) {
    for (int j = 0; j < 8; ++j) {
      const double sw = values.w[i] * values.stencils[i].weight[j];
      num[values.stencils[i].node[j]] += sw * residual[i];
      den[values.stencils[i].node[j]] += sw;
    }
  }
  SpreadOverNodes(grid, reach, &num);
  SpreadOverNodes(grid, reach, &den);
  for (int node = 0; node < grid.Cells(); ++node) {
    num[node] = den[node] > 0 ? num[node] / (den[node] + weight) : 0.0;
  }
  return num;
}

}  // namespace

PriorFitResult FitPrior(const MeasuredPrior& prior, const std::vector<Observation>& observations,
                        const PriorFitOptions& options) {
  options.Validate();
  const brdf::RusinkiewiczGrid& grid = prior.grid;
  const Rows values = RowsOf(prior, observations, false);
  const Rows bounds = RowsOf(prior, observations, true);
  const Eigen::Index n = values.Size();
  if (n == 0) throw Error("prior fit: no usable sample (every one below the surface or empty)");
  const Eigen::MatrixXd& b = values.b;
  const Eigen::VectorXd& w = values.w;
  const double inv_s2 = 1 / (prior.noise_sigma * prior.noise_sigma);
  const Eigen::MatrixXd data_normal = b.transpose() * w.asDiagonal() * b * inv_s2;

  PriorFitResult result;
  result.observations = static_cast<int>(n);
  result.bounds = static_cast<int>(bounds.Size());
  for (int ch = 0; ch < 3; ++ch) {
    const Eigen::VectorXd& qc = values.q[ch];
    const Eigen::VectorXd data_rhs = b.transpose() * (w.asDiagonal() * (qc - values.mu)) * inv_s2;
    const ChannelPrior cp = PriorOf(prior, options.bandwidth, data_normal, data_rhs);
    result.neighbour_weights[ch] = cp.weights;
    int active = 0;
    result.coefficients[ch] = SolveChannel(
        data_normal + cp.precision, data_rhs + cp.precision * cp.mean, bounds, ch, inv_s2, &active);
    result.bounds_active = std::max(result.bounds_active, active);
    const Eigen::VectorXd table = prior.mean + prior.components * result.coefficients[ch];
    const Eigen::VectorXd residual = qc - values.mu - b * result.coefficients[ch];
    const double rms = std::sqrt(w.dot(residual.cwiseAbs2()) / w.sum());
    result.misfit = std::max(result.misfit, rms);
    result.table[ch].assign(table.data(), table.data() + table.size());
    if (options.correct) {
      // Spread over the neighbours first, then each node's own samples correct what is left,
      // so the table still follows the samples where they are.
      const auto apply = [&](const std::vector<double>& delta) {
        for (int node = 0; node < grid.Cells(); ++node) result.table[ch][node] += delta[node];
      };
      Eigen::VectorXd left = residual;
      if (options.correction_reach > 0) {
        const std::vector<double> spread =
            CorrectionOf(grid, values, left, options.correction_reach, prior.correction_weight);
        apply(spread);
        for (Eigen::Index i = 0; i < n; ++i) {
          for (int j = 0; j < 8; ++j) {
            left[i] -= values.stencils[i].weight[j] * spread[values.stencils[i].node[j]];
          }
        }
      }
      apply(CorrectionOf(grid, values, left, 0, prior.correction_weight));
    }
    // The table's valid range (rusinkiewicz_table.h).
    for (double& value : result.table[ch]) value = std::clamp(value, std::log(grid.epsilon), 80.0);
  }
  result.outside_prior = result.misfit > options.misfit_limit;
  return result;
}

}  // namespace brdfrig::prior
