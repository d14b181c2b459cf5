#include "coverage/prior_objective.h"

#include <Eigen/Cholesky>
#include <algorithm>

#include "brdf/rusinkiewicz_table.h"
#include "common/error.h"
#include "geometry/camera.h"

namespace brdfrig::coverage {

PriorObjective::PriorObjective(const prior::MeasuredPrior& prior, int components,
                               int points_per_side)
    : prior_(prior),
      k_(std::clamp(components, 1, std::min(prior.Components(), kMaxComponents))),
      points_per_side_(std::max(points_per_side, 2)) {
  components_ = prior.components.leftCols(k_);
  inverse_variances_ = prior.variances.head(k_).cwiseInverse();
  const std::vector<double> measure = brdf::NodeMeasure(prior.grid);
  const Eigen::Map<const Eigen::VectorXd> w(measure.data(),
                                            static_cast<Eigen::Index>(measure.size()));
  metric_ = components_.transpose() * w.asDiagonal() * components_;
  // M = R Rᵀ; a component that lives only below the horizon makes M singular, hence the jitter.
  Eigen::MatrixXd jittered = metric_;
  jittered.diagonal().array() += 1e-12 * metric_.diagonal().mean();
  metric_root_ = Eigen::LLT<Eigen::MatrixXd>(jittered).matrixL();
}

Eigen::MatrixXd PriorObjective::Information(const geometry::RigGeometry& rig,
                                            const geometry::AxisPositions& axes) const {
  const geometry::CameraPose pose = rig.CameraAt(axes);
  const geometry::Vec3 camera = pose.CenterInWorld();
  const geometry::Vec3 light = rig.LightAt(axes);
  std::vector<Eigen::VectorXd> rows;
  const int n = points_per_side_;
  for (int iy = 0; iy < n; ++iy) {
    for (int ix = 0; ix < n; ++ix) {
      const geometry::Vec3 x((ix / (n - 1.0) - 0.5) * rig.target.cutout_width,
                             (iy / (n - 1.0) - 0.5) * rig.target.cutout_height, 0);
      Eigen::Vector2d px;
      if (!geometry::ProjectToPixel(rig.intrinsics, pose, x, &px) || px.x() < 0 || px.y() < 0 ||
          px.x() >= rig.intrinsics.width || px.y() >= rig.intrinsics.height) {
        continue;
      }
      const brdf::Vec3 l = (light - x).normalized(), v = (camera - x).normalized();
      if (l.z() <= 0 || v.z() <= 0) continue;
      const brdf::Stencil s = brdf::StencilAt(prior_.grid, brdf::ToHalfDiffAngles(l, v));
      Eigen::VectorXd b = Eigen::VectorXd::Zero(k_);
      for (int j = 0; j < 8; ++j) {
        if (s.weight[j] != 0) b += s.weight[j] * components_.row(s.node[j]).transpose();
      }
      rows.push_back(std::move(b));
    }
  }
  if (rows.empty()) return {};
  // Every photo weighs 1000 in all, as in the fit (reconstruct/prior_rung.h).
  const double w = 1000.0 / static_cast<double>(rows.size());
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(k_, k_);
  for (const Eigen::VectorXd& b : rows) info.selfadjointView<Eigen::Lower>().rankUpdate(b, w);
  return info.selfadjointView<Eigen::Lower>();
}

double PriorObjective::ExpectedError(const Eigen::MatrixXd& total) const {
  // Called ~10⁵ times per design: matrices of at most kMaxComponents on the stack.
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                              kMaxComponents, kMaxComponents>;
  Small precision = total / (prior_.noise_sigma * prior_.noise_sigma);
  precision.diagonal() += inverse_variances_;
  const Eigen::LLT<Small> llt(precision);
  Small x = metric_root_;
  llt.matrixL().solveInPlace(x);  // trace(M P⁻¹) = ‖L⁻¹ R‖² (P = L Lᵀ, M = R Rᵀ)
  return x.squaredNorm();
}

double PriorObjective::PriorError() const {
  return metric_.diagonal().dot(inverse_variances_.cwiseInverse());
}

double PriorObjective::RmsPerNode(double error) const {
  return std::sqrt(error / static_cast<double>(prior_.grid.Cells()));
}

double PriorObjective::LeaveOneOutError(const Eigen::MatrixXd& total) const {
  const Eigen::MatrixXd coefficients = prior_.training_coefficients.leftCols(k_);
  const Eigen::Index rows = coefficients.rows();
  const Eigen::Index materials = rows / 3;
  if (materials < 3) return ExpectedError(total);
  const Eigen::MatrixXd data = total / (prior_.noise_sigma * prior_.noise_sigma);
  const Eigen::MatrixXd all = coefficients.transpose() * coefficients;  // K × K
  const Eigen::VectorXd sum = coefficients.colwise().sum().transpose();
  double error = 0;
  for (Eigen::Index m = 0; m < materials; ++m) {
    const Eigen::MatrixXd own = coefficients.middleRows(3 * m, 3);  // 3 × K
    const double n = static_cast<double>(rows - 3);
    const Eigen::VectorXd mean = (sum - own.colwise().sum().transpose()) / n;
    Eigen::MatrixXd cov =
        (all - own.transpose() * own) / (n - 1) - mean * mean.transpose() * (n / (n - 1));
    cov.diagonal().array() += 1e-9 * cov.diagonal().mean();
    const Eigen::LLT<Eigen::MatrixXd> cov_llt(cov);
    Eigen::MatrixXd precision = data + cov_llt.solve(Eigen::MatrixXd::Identity(k_, k_));
    const Eigen::LLT<Eigen::MatrixXd> llt(precision);
    for (int c = 0; c < 3; ++c) {
      // Noise-free observations at the plan's points: estimate = mean + P⁻¹ D (truth − mean).
      const Eigen::VectorXd offset = own.row(c).transpose() - mean;
      const Eigen::VectorXd estimate = llt.solve(data * offset);
      const Eigen::VectorXd e = estimate - offset;
      error += e.dot(metric_ * e);
    }
  }
  return error / static_cast<double>(rows);
}

}  // namespace brdfrig::coverage
