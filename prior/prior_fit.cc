#include "prior/prior_fit.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::prior {

void PriorFitOptions::Validate() const {
  CheckOption(misfit_limit > 0 && std::isfinite(misfit_limit), "PriorFitOptions.misfit_limit",
              misfit_limit, "positive");
}

PriorFitResult FitPrior(const MeasuredPrior& prior, const std::vector<Observation>& observations,
                        const PriorFitOptions& options) {
  options.Validate();
  const brdf::RusinkiewiczGrid& grid = prior.grid;
  const int k = prior.Components();
  std::vector<brdf::Stencil> stencils;
  std::vector<double> weights;
  std::array<std::vector<double>, 3> q;
  for (const Observation& o : observations) {
    if (!(o.weight > 0) || o.l.z() <= 0 || o.v.z() <= 0 || !o.f.isFinite().all()) continue;
    stencils.push_back(brdf::StencilAt(grid, brdf::ToHalfDiffAngles(o.l, o.v)));
    weights.push_back(o.weight);
    const double c = brdf::CosineProduct(grid, o.l, o.v);
    for (int ch = 0; ch < 3; ++ch) q[ch].push_back(brdf::MapValue(grid, o.f[ch], c));
  }
  const auto n = static_cast<Eigen::Index>(stencils.size());
  if (n == 0) throw Error("prior fit: no usable sample (every one below the surface or empty)");
  Eigen::MatrixXd b(n, k);
  Eigen::VectorXd mu(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    b.row(i).setZero();
    mu[i] = 0;
    for (int j = 0; j < 8; ++j) {
      const double w = stencils[i].weight[j];
      if (w == 0) continue;
      b.row(i) += w * prior.components.row(stencils[i].node[j]);
      mu[i] += w * prior.mean[stencils[i].node[j]];
    }
  }
  const Eigen::Map<const Eigen::VectorXd> w(weights.data(), n);
  const double inv_s2 = 1 / (prior.noise_sigma * prior.noise_sigma);
  Eigen::MatrixXd normal = b.transpose() * w.asDiagonal() * b * inv_s2;
  normal.diagonal() += prior.variances.cwiseInverse();
  const Eigen::LDLT<Eigen::MatrixXd> solver(normal);

  PriorFitResult result;
  result.observations = static_cast<int>(n);
  for (int ch = 0; ch < 3; ++ch) {
    const Eigen::Map<const Eigen::VectorXd> qc(q[ch].data(), n);
    const Eigen::VectorXd rhs = b.transpose() * (w.asDiagonal() * (qc - mu)) * inv_s2;
    result.coefficients[ch] = solver.solve(rhs);
    const Eigen::VectorXd table = prior.mean + prior.components * result.coefficients[ch];
    const Eigen::VectorXd residual = qc - mu - b * result.coefficients[ch];
    const double rms = std::sqrt(w.dot(residual.cwiseAbs2()) / w.sum());
    result.misfit = std::max(result.misfit, rms);
    result.table[ch].assign(table.data(), table.data() + table.size());
    if (options.correct) {
      std::vector<double> num(grid.Cells(), 0.0), den(grid.Cells(), 0.0);
      for (Eigen::Index i = 0; i < n; ++i) {
        for (int j = 0; j < 8; ++j) {
          const double sw = w[i] * stencils[i].weight[j];
          num[stencils[i].node[j]] += sw * residual[i];
          den[stencils[i].node[j]] += sw;
        }
      }
      for (int node = 0; node < grid.Cells(); ++node) {
        if (den[node] > 0) {
          result.table[ch][node] += num[node] / (den[node] + prior.correction_weight);
        }
      }
    }
    // The table's valid range (rusinkiewicz_table.h).
    for (double& value : result.table[ch]) value = std::clamp(value, std::log(grid.epsilon), 80.0);
  }
  result.outside_prior = result.misfit > options.misfit_limit;
  return result;
}

}  // namespace brdfrig::prior
