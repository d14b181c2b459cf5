#include "reconstruct/light_refine.h"

#include <ceres/ceres.h>

#include <cmath>

#include "brdf/logistic.h"
#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::reconstruct {
namespace {

struct PixelRecord {
  geometry::Vec3 x;     // plane point
  geometry::Vec3 v;     // unit direction to the camera
  double log_value[3];  // ln(HDR / k), R, G, B
};

// Residuals ln m_c(theta(l)) − ln(HDR_c / (k_c E(l))) for the three channels of one pixel.
struct LightLobeResidual {
  const PixelRecord* pixel;
  geometry::Vec3 base, d0, e1, e2;
  double distance;

  template <typename T>
  bool operator()(const T* light, const T* r, const T* g, const T* b, T* residual) const {
    using V = Eigen::Matrix<T, 3, 1>;
    V dir = d0.cast<T>() + light[0] * e1.cast<T>() + light[1] * e2.cast<T>();
    dir /= dir.norm();
    const V to_light = base.cast<T>() + T(distance) * dir - pixel->x.cast<T>();
    const T d2 = to_light.squaredNorm();
    const V l = to_light / sqrt(d2);
    const T log_e = log(l.z()) - log(d2);
    const V mirror(-l.x(), -l.y(), l.z());
    const V v = pixel->v.cast<T>();
    const T cross = v.cross(mirror).squaredNorm();
    const T theta = atan2(sqrt(cross + T(1e-30)), v.dot(mirror));
    const T* params[3] = {r, g, b};
    for (int c = 0; c < 3; ++c) {
      const T* p = params[c];
      const T z = (theta - p[3]) / exp(p[2]);
      const T sigma = brdf::Logistic(-z);
      const T m = exp(p[0]) + exp(p[1]) * sigma;
      residual[c] = log(m) - T(pixel->log_value[c]) + log_e;
    }
    return true;
  }
};

}  // namespace

void LightRefineOptions::Validate() const {
  CheckOption(max_pixels >= 100, "LightRefineOptions.max_pixels", max_pixels, ">= 100");
  CheckOption(max_iterations >= 1, "LightRefineOptions.max_iterations", max_iterations, ">= 1");
  CheckOption(max_shift_rad > 0, "LightRefineOptions.max_shift_rad", max_shift_rad, "> 0");
}

LightRefinement RefineLight(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                            const geometry::TargetGeometry& target,
                            const SampleOptions& sample_options, const geometry::Vec3& start_light,
                            const Radiometry& radiometry, const SliceFit& start_fit,
                            const LightRefineOptions& options) {
  options.Validate();
  LightRefinement out;
  out.position = start_light;
  if (!options.enabled || start_fit.flat) return out;

  const SampleRegion region = SampleRegionOf(view, target, sample_options);
  const PlaneView::Box& box = region.box;
  const long area = static_cast<long>(box.x1 - box.x0) * (box.y1 - box.y0);
  const int stride =
      std::max(1, static_cast<int>(std::sqrt(static_cast<double>(area) / options.max_pixels)));
  std::vector<PixelRecord> pixels;
  for (int y = box.y0; y < box.y1; y += stride) {
    for (int x = box.x0; x < box.x1; x += stride) {
      if (!valid.at<uchar>(y, x)) continue;
      const auto p = view.PointAt(x, y);
      if (!p || !region.Contains(*p)) continue;
      const cv::Vec3f value = radiance.at<cv::Vec3f>(y, x);
      PixelRecord record{*p, (view.camera_centre() - *p).normalized(), {}};
      bool ok = true;
      const cv::Vec3d k = radiometry.ScaleAt(x, y);
      for (int c = 0; c < 3; ++c) {
        const double v = value[2 - c] / k[2 - c];  // B,G,R → R,G,B
        ok = ok && v > 0 && std::isfinite(v);
        record.log_value[c] = ok ? std::log(v) : 0;
      }
      if (ok) pixels.push_back(record);
    }
  }
  if (pixels.size() < 100) return out;

  // The light as base + distance · normalize(d0 + a e1 + b e2), base = the cut-out's centre.
  const geometry::Vec3 base = geometry::Vec3::Zero();
  const geometry::Vec3 d0 = (start_light - base).normalized();
  const double distance = (start_light - base).norm();
  const geometry::Vec3 e1 = d0.unitOrthogonal();
  const geometry::Vec3 e2 = d0.cross(e1);
  double light[2] = {0, 0};
  std::array<std::array<double, 4>, 3> lobes;
  for (int c = 0; c < 3; ++c) {
    const brdf::LobeParams& p = start_fit.channel[c].params;
    const double a2 = std::max(p.a2, 1e-12);
    lobes[c] = {std::log(a2), std::log(std::max(p.a1 - a2, 1e-6 * a2)), std::log(p.h), p.x0};
  }
  ceres::Problem problem;
  ceres::CauchyLoss* loss = new ceres::CauchyLoss(0.2);
  for (const PixelRecord& pixel : pixels) {
    auto* cost = new ceres::AutoDiffCostFunction<LightLobeResidual, 3, 2, 4, 4, 4>(
        new LightLobeResidual{&pixel, base, d0, e1, e2, distance});
    problem.AddResidualBlock(cost, loss, light, lobes[0].data(), lobes[1].data(), lobes[2].data());
  }
  // Bounds keep every trial step finite (exp of a wild log-amplitude overflows): amplitudes
  // within e^±10 of the start, the lobe width up to pi, the light within ~30° of its start.
  for (auto& lobe : lobes) {
    for (int k = 0; k < 2; ++k) {
      problem.SetParameterLowerBound(lobe.data(), k, lobe[static_cast<std::size_t>(k)] - 10);
      problem.SetParameterUpperBound(lobe.data(), k, lobe[static_cast<std::size_t>(k)] + 10);
    }
    problem.SetParameterLowerBound(lobe.data(), 2, std::min(lobe[2], std::log(1e-4)));
    problem.SetParameterUpperBound(lobe.data(), 2, std::max(lobe[2], std::log(M_PI)));
  }
  for (int k = 0; k < 2; ++k) {
    problem.SetParameterLowerBound(light, k, -0.5);
    problem.SetParameterUpperBound(light, k, 0.5);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-12;
  solver.parameter_tolerance = 1e-12;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (!summary.IsSolutionUsable()) return out;
  const geometry::Vec3 dir = (d0 + light[0] * e1 + light[1] * e2).normalized();
  out.shift_rad = std::atan2(d0.cross(dir).norm(), d0.dot(dir));
  if (!(out.shift_rad <= options.max_shift_rad)) return out;
  out.position = base + distance * dir;
  out.accepted = true;
  return out;
}

}  // namespace brdfrig::reconstruct
