// The sphere test: the fitted and the true material on an orthographic sphere under a
// directional light at several angles from the view direction (0° = behind the camera, 80° =
// grazing), so a fit is judged over the whole hemisphere and not only where it was photographed.
//
// Protocol (named in every result): per pixel the linear radiance f(l, v, n) · cos θi for a unit
// directional light; both images are divided by the truth's 99th percentile over sphere pixels
// (all channels pooled; the same scale for the fit), clamped to [0, 1], sRGB-encoded, and
// compared by PSNR (peak 1) over sphere pixels. Beside it the relative RMSE in linear radiance,
// unclamped: sqrt(mean (fit − truth)²) / sqrt(mean truth²) over sphere pixels and channels.
// Both figures are exposure independent: scaling both materials by k changes neither.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "common/srgb.h"  // the protocol's encoding

namespace brdfrig::evaluate {

struct SphereTestOptions {
  int resolution = 128;  // image side in pixels; the sphere fills it
  std::vector<double> light_angles_deg = {0, 30, 60, 80};  // from the view direction, < 90
  double percentile = 0.99;  // of the truth's sphere radiance that maps to display white
  bool keep_images = false;  // keep the sRGB images (CV_8UC3, B,G,R) for reports
  void Validate() const;     // throws OptionsError
};

struct SphereLight {
  double light_angle_deg = 0;
  double psnr_db = 0;        // +inf for identical images
  double relative_rmse = 0;  // linear radiance, unclamped
  double scale = 0;          // the truth's percentile radiance (1/sr · cos) that maps to 1
  long pixels = 0;           // sphere pixels compared
  cv::Mat truth_image, fitted_image;  // display images when keep_images
};

struct SphereTestResult {
  std::vector<SphereLight> lights;
  double mean_psnr_db = 0;  // over lights
  double worst_psnr_db = 0;
  double mean_relative_rmse = 0;
  std::string protocol;
  std::string Report() const;  // one line
};

// Linear radiance f · cos θi of `brdf` on the sphere for a light `light_angle` (radians) from
// the view direction; CV_32FC3 (B,G,R); pixels off the sphere are 0. `mask` (optional) gets the
// sphere pixels (CV_8UC1, 255 on the sphere).
cv::Mat SphereRadiance(const brdf::Brdf& brdf, double light_angle, int resolution,
                       cv::Mat* mask = nullptr);

SphereTestResult SphereTest(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                            const SphereTestOptions& options = {});

}  // namespace brdfrig::evaluate
