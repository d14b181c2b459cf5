#include "reconstruct/samples.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "brdf/slice_model.h"
#include "common/error.h"
#include "common/option_check.h"
#include "common/parallel.h"

namespace brdfrig::reconstruct {

void SampleOptions::Validate() const {
  CheckOption(edge_margin >= 0 && edge_margin < 0.4, "SampleOptions.edge_margin", edge_margin,
              "in [0, 0.4)");
  CheckOption(bin_width >= 0, "SampleOptions.bin_width", bin_width, ">= 0");
}

double BrdfSamples::ThetaMin() const {
  return theta.empty() ? 0 : *std::min_element(theta.begin(), theta.end());
}
double BrdfSamples::ThetaMax() const {
  return theta.empty() ? 0 : *std::max_element(theta.begin(), theta.end());
}

SampleRegion SampleRegionOf(const PlaneView& view, const geometry::TargetGeometry& target,
                            const SampleOptions& options) {
  const double margin = options.edge_margin * std::min(target.cutout_width, target.cutout_height);
  SampleRegion region;
  region.half_w = target.cutout_width / 2 - margin;
  region.half_h = target.cutout_height / 2 - margin;
  region.box = view.PixelBox(region.half_w, region.half_h);
  return region;
}

BrdfSamples ExtractSamples(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                           const geometry::Vec3& light, const Radiometry& radiometry,
                           const geometry::TargetGeometry& target, const SampleOptions& options) {
  options.Validate();
  const geometry::Vec3 n = geometry::Vec3::UnitZ();
  const SampleRegion region = SampleRegionOf(view, target, options);
  const PlaneView::Box& box = region.box;
  const geometry::Vec3& camera = view.camera_centre();

  BrdfSamples out;
  out.theta_in = brdf::ComputeSliceAngles(light.normalized(), camera.normalized(), n).theta_in;

  struct RowSamples {
    std::vector<double> theta;
    std::vector<std::array<double, 3>> f;
    int invalid = 0;
    double spread = 0, step_sum = 0;
    int steps = 0;
  };
  std::vector<RowSamples> rows(static_cast<std::size_t>(std::max(box.y1 - box.y0, 0)));
  ParallelFor(rows.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      const int y = box.y0 + static_cast<int>(r);
      RowSamples& row = rows[r];
      double previous_theta = -1;
      for (int x = box.x0; x < box.x1; ++x) {
        const auto p = view.PointAt(x, y);
        if (!p || !region.Contains(*p)) {
          previous_theta = -1;
          continue;
        }
        if (!valid.at<uchar>(y, x)) {
          ++row.invalid;
          previous_theta = -1;
          continue;
        }
        const geometry::Vec3 l = (light - *p).normalized();
        const geometry::Vec3 v = (camera - *p).normalized();
        const brdf::SliceAngles angles = brdf::ComputeSliceAngles(l, v, n);
        const double e = PointLightIrradiance(light, *p);
        const cv::Vec3f value = radiance.at<cv::Vec3f>(y, x);
        if (!(e > 0) || !std::isfinite(value[0]) || !std::isfinite(value[1]) ||
            !std::isfinite(value[2])) {
          ++row.invalid;
          continue;
        }
        // B,G,R image → R,G,B material channels.
        const cv::Vec3d k = radiometry.ScaleAt(x, y);
        row.f.push_back({value[2] / (k[2] * e), value[1] / (k[1] * e), value[0] / (k[0] * e)});
        row.theta.push_back(angles.theta);
        row.spread = std::max(row.spread, std::abs(angles.theta_in - out.theta_in));
        if (previous_theta >= 0) {
          row.step_sum += std::abs(angles.theta - previous_theta);
          ++row.steps;
        }
        previous_theta = angles.theta;
      }
    }
  });
  double step_sum = 0;
  int steps = 0;
  for (const RowSamples& row : rows) {
    out.theta.insert(out.theta.end(), row.theta.begin(), row.theta.end());
    out.f.insert(out.f.end(), row.f.begin(), row.f.end());
    out.pixels_invalid += row.invalid;
    out.theta_in_spread = std::max(out.theta_in_spread, row.spread);
    step_sum += row.step_sum;
    steps += row.steps;
  }
  out.pixels_used = static_cast<int>(out.theta.size());
  out.angular_pixel_size = steps > 0 ? step_sum / steps : 0;
  out.weight.assign(out.theta.size(), 1.0);
  if (options.bin_width > 0 && !out.theta.empty()) {
    // Mean per bin (unbiased under zero-mean noise), at the bin's mean theta.
    std::map<long, std::pair<double, std::array<double, 4>>> bins;  // count, (theta, r, g, b) sums
    for (std::size_t i = 0; i < out.theta.size(); ++i) {
      auto& [count, sums] = bins[static_cast<long>(std::floor(out.theta[i] / options.bin_width))];
      count += 1;
      sums[0] += out.theta[i];
      for (int c = 0; c < 3; ++c) sums[c + 1] += out.f[i][c];
    }
    out.theta.clear();
    out.f.clear();
    out.weight.clear();
    for (const auto& [bin, entry] : bins) {
      const auto& [count, sums] = entry;
      out.theta.push_back(sums[0] / count);
      out.f.push_back({sums[1] / count, sums[2] / count, sums[3] / count});
      out.weight.push_back(count);
    }
  }
  return out;
}

}  // namespace brdfrig::reconstruct
