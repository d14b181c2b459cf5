// Radiometric calibration from the paper mask. The paper is a Lambertian reflector of known
// albedo ρ, so where it is lit with irradiance factor E = cos(θ_l)/d² its HDR value is
// k·ρ/π·E, with k the unknown product of light intensity and camera gain (per channel, which
// also white-balances). k is the median of HDR·π/(ρ·E) over the paper; a sample pixel then has
// f = HDR / (k·E): a BRDF in 1/sr.
#pragma once

#include <array>
#include <opencv2/core.hpp>

#include "geometry/rig_geometry.h"
#include "reconstruct/plane_view.h"

namespace brdfrig::reconstruct {

struct RadiometryOptions {
  double margin = 0.15;  // fraction of the paper band (cut-out edge to paper edge) left out
  int stride = 2;        // use every stride-th pixel in x and y
  // Paper spread (median absolute deviation / median) above which the calibration is flagged:
  // a clean paper is within a few percent; more means noise, clipping or uneven light.
  double warn_spread = 0.15;
  // k as a quadratic surface over the image, fitted to the paper ring around the cut-out and
  // evaluated inside it: absorbs vignetting and uneven light (a flat field from the paper).
  // false: one k per channel (the median).
  bool flat_field = true;
  void Validate() const;
};

struct Radiometry {
  cv::Vec3d scale;             // k per channel (B, G, R), HDR units per (W/sr · 1/m² · 1/sr)
  int paper_pixels = 0;        // pixels used
  double relative_spread = 0;  // median absolute deviation / median (green): how Lambertian
                               // and evenly lit the paper looks
  // Flat field: k_c(x, y) = scale_c · (1 + Σ coeffs_c · [1, u, v, u², uv, v²]), u, v = pixel
  // coordinates relative to the image centre over its half width. Zero without a flat field.
  std::array<std::array<double, 6>, 3> field{};
  int width = 0, height = 0;
  cv::Vec3d ScaleAt(double x, double y) const;
};

// Throws brdfrig::Error when the paper cannot be seen (fewer than 100 usable pixels).
Radiometry CalibrateFromPaper(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                              const geometry::Vec3& light, const geometry::TargetGeometry& target,
                              const RadiometryOptions& options);

}  // namespace brdfrig::reconstruct
