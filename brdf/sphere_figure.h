// The sphere test's PSNR (evaluate/sphere_test.h, same protocol and numbers) computed below
// evaluate/, without images or OpenCV, so that reconstruct/ can state what exporting a
// material to glTF costs when it writes the material (reconstruct/gltf_fit.h):
// an orthographic sphere under a unit directional light `angle` from the view direction,
// f · cos θi per pixel, both images divided by the truth's 99th percentile over sphere
// pixels, clamped, sRGB-encoded, PSNR over sphere pixels (peak 1), mean and worst over lights.
// tests/export/sphere_figure_test.cc checks it against evaluate::SphereTest.
#pragma once

#include <string>
#include <vector>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

struct SphereFigureOptions {
  int resolution = 128;
  std::vector<double> light_angles_deg = {0, 30, 60, 80};
  double percentile = 0.99;
  void Validate() const;  // throws OptionsError
};

struct SphereFigure {
  std::vector<double> psnr_db;  // per light, as light_angles_deg
  double mean_psnr_db = 0, worst_psnr_db = 0;
};

SphereFigure SpherePsnr(const Brdf& truth, const Brdf& fitted,
                        const SphereFigureOptions& options = {});

}  // namespace brdfrig::brdf
