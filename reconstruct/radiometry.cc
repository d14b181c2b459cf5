#include "reconstruct/radiometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.h"

namespace brdfrig::reconstruct {
namespace {

double Median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

void RadiometryOptions::Validate() const {
  if (!(margin >= 0 && margin < 0.5))
    throw OptionsError("RadiometryOptions.margin must be in [0, 0.5)");
  if (stride < 1) throw OptionsError("RadiometryOptions.stride must be >= 1");
}

Radiometry CalibrateFromPaper(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                              const rig::Vec3& light, const rig::TargetGeometry& target,
                              const RadiometryOptions& options) {
  options.Validate();
  const double band_x = (target.paper_width - target.cutout_width) / 2;
  const double band_y = (target.paper_height - target.cutout_height) / 2;
  const double in_x = target.cutout_width / 2 + options.margin * band_x;
  const double in_y = target.cutout_height / 2 + options.margin * band_y;
  const double out_x = target.paper_width / 2 - options.margin * band_x;
  const double out_y = target.paper_height / 2 - options.margin * band_y;
  const PlaneView::Box box = view.PixelBox(out_x, out_y);
  std::array<std::vector<double>, 3> k;
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
      for (int c = 0; c < 3; ++c) {
        if (std::isfinite(value[c])) k[c].push_back(value[c] * M_PI / (target.paper_albedo * e));
      }
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
  return result;
}

}  // namespace brdfrig::reconstruct
