#include "reconstruct/radiometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.h"
#include "common/median.h"
#include "common/option_check.h"

namespace brdfrig::reconstruct {

cv::Vec3d Radiometry::ScaleAt(double x, double y) const {
  if (width == 0) return scale;
  const double u = (x - 0.5 * width) / (0.5 * width);
  const double v = (y - 0.5 * height) / (0.5 * width);
  const double basis[6] = {1, u, v, u * u, u * v, v * v};
  cv::Vec3d k;
  for (int c = 0; c < 3; ++c) {
    double f = 1;
    for (int j = 0; j < 6; ++j) f += field[c][j] * basis[j];
    k[c] = scale[c] * std::max(f, 0.05);  // a wild extrapolation must not flip the sign
  }
  return k;
}

void RadiometryOptions::Validate() const {
  CheckOption(margin >= 0 && margin < 0.5, "RadiometryOptions.margin", margin, "in [0, 0.5)");
  CheckOption(stride >= 1, "RadiometryOptions.stride", stride, ">= 1");
  CheckOption(warn_spread > 0, "RadiometryOptions.warn_spread", warn_spread, "> 0");
}

Radiometry CalibrateFromPaper(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                              const geometry::Vec3& light, const geometry::TargetGeometry& target,
                              const RadiometryOptions& options) {
  options.Validate();
  // The bare paper: from the cut-out's edge to the paper's, or on a marker mask to the ring of
  // markers (beyond it the print — markers, scale bar, title — is not the paper's albedo).
  const double outer_x =
      target.markers ? target.cutout_width / 2 + target.markers->gap : target.paper_width / 2;
  const double outer_y =
      target.markers ? target.cutout_height / 2 + target.markers->gap : target.paper_height / 2;
  const double band_x = outer_x - target.cutout_width / 2;
  const double band_y = outer_y - target.cutout_height / 2;
  const double in_x = target.cutout_width / 2 + options.margin * band_x;
  const double in_y = target.cutout_height / 2 + options.margin * band_y;
  const double out_x = outer_x - options.margin * band_x;
  const double out_y = outer_y - options.margin * band_y;
  const PlaneView::Box box = view.PixelBox(out_x, out_y);
  std::array<std::vector<double>, 3> k;
  std::vector<cv::Point> at;
  for (int y = box.y0; y < box.y1; y += options.stride) {
    for (int x = box.x0; x < box.x1; x += options.stride) {
      if (!valid.at<uchar>(y, x)) continue;
      const auto p = view.PointAt(x, y);
      if (!p) continue;
      const double ax = std::abs(p->x()), ay = std::abs(p->y());
      if (ax > out_x || ay > out_y || (ax < in_x && ay < in_y)) continue;
      const double e = PointLightIrradiance(light, *p);
      if (!(e > 0)) continue;
      const cv::Vec3f value = radiance.at<cv::Vec3f>(y, x);
      if (!std::isfinite(value[0]) || !std::isfinite(value[1]) || !std::isfinite(value[2]))
        continue;
      for (int c = 0; c < 3; ++c) k[c].push_back(value[c] * M_PI / (target.paper_albedo * e));
      at.emplace_back(x, y);
    }
  }
  if (k[1].size() < 100) {
    throw Error("radiometric calibration: only " + std::to_string(k[1].size()) +
                " usable paper pixels (is the paper in view and not clipped in every exposure?)");
  }
  Radiometry result;
  result.paper_pixels = static_cast<int>(k[1].size());
  for (int c = 0; c < 3; ++c) result.scale[c] = Median(k[c]);
  std::vector<double> deviation(k[1].size());
  for (std::size_t i = 0; i < k[1].size(); ++i) deviation[i] = std::abs(k[1][i] - result.scale[1]);
  result.relative_spread = Median(deviation) / std::max(result.scale[1], 1e-300);
  if (!(result.scale[0] > 0 && result.scale[1] > 0 && result.scale[2] > 0)) {
    throw Error("radiometric calibration: the paper looks black (check the exposures)");
  }
  result.width = radiance.cols;
  result.height = radiance.rows;
  if (options.flat_field) {
    // Least squares for k/scale − 1 = Σ coeffs · basis over the paper pixels within ±50%
    // (specks, dust and the cut-out's blurred edge are left out).
    for (int c = 0; c < 3; ++c) {
      cv::Matx<double, 6, 6> ata = cv::Matx<double, 6, 6>::zeros();
      cv::Matx<double, 6, 1> atb = cv::Matx<double, 6, 1>::zeros();
      for (std::size_t i = 0; i < at.size(); ++i) {
        const double r = k[c][i] / result.scale[c] - 1;
        if (std::abs(r) > 0.5) continue;
        const double u = (at[i].x - 0.5 * radiance.cols) / (0.5 * radiance.cols);
        const double v = (at[i].y - 0.5 * radiance.rows) / (0.5 * radiance.cols);
        const cv::Matx<double, 6, 1> b(1, u, v, u * u, u * v, v * v);
        ata += b * b.t();
        atb += b * r;
      }
      cv::Matx<double, 6, 1> coeffs;
      if (cv::solve(ata, atb, coeffs, cv::DECOMP_SVD)) {
        for (int j = 0; j < 6; ++j) result.field[c][j] = coeffs(j);
      }
    }
  }
  return result;
}

}  // namespace brdfrig::reconstruct
