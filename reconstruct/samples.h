// BRDF samples of one capture position: every valid pixel of the sample region (inside the
// cut-out, away from its edges) becomes (theta_in, theta, f_rgb) with f in 1/sr. The slice
// model's theta_in for the position is the incidence angle at the cut-out's centre; theta is
// measured per pixel. Optional binning by theta averages samples in bins of fixed width.
#pragma once

#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "common/angles.h"
#include "geometry/rig_geometry.h"
#include "reconstruct/plane_view.h"
#include "reconstruct/radiometry.h"

namespace brdfrig::reconstruct {

struct SampleOptions {
  double edge_margin = 0.04;  // fraction of the cut-out's size excluded along its border
  // Radians of theta per bin; 0 = every pixel a sample. The default (0.02°) is well below any
  // resolvable lobe width and cuts the fit's time by two orders of magnitude.
  double bin_width = Radians(0.02);
  void Validate() const;
};

struct BrdfSamples {
  double theta_in = 0;                   // the slice's incidence angle (radians)
  std::vector<double> theta;             // per sample (radians)
  std::vector<std::array<double, 3>> f;  // per sample, R, G, B (1/sr)
  std::vector<double> weight;            // pixels per sample (1 without binning)
  int pixels_used = 0;
  int pixels_invalid = 0;         // clipped in every exposure (excluded)
  double theta_in_spread = 0;     // max |theta_in(pixel) − theta_in| over the samples
  double angular_pixel_size = 0;  // typical theta step between neighbouring pixels (radians)
  double ThetaMin() const;
  double ThetaMax() const;
};

// The part of the cut-out whose pixels become samples (the cut-out less `edge_margin` along its
// border, |x| <= half_w, |y| <= half_h on the plane) and the pixel box covering it. Shared by
// the slice samples, the direction samples, the light refinement and the photo prediction so
// all use the very same pixels (tests/reconstruct/sample_region_test).
struct SampleRegion {
  double half_w = 0, half_h = 0;
  PlaneView::Box box;
  bool Contains(const geometry::Vec3& p) const {
    return std::abs(p.x()) <= half_w && std::abs(p.y()) <= half_h;
  }
};
SampleRegion SampleRegionOf(const PlaneView& view, const geometry::TargetGeometry& target,
                            const SampleOptions& options);

BrdfSamples ExtractSamples(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                           const geometry::Vec3& light, const Radiometry& radiometry,
                           const geometry::TargetGeometry& target, const SampleOptions& options);

}  // namespace brdfrig::reconstruct
