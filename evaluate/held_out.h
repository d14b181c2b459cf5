// The seed's evaluation: a photo not used for fitting is compared with a rendering of the fitted
// model under the same geometry. Every PSNR comes two ways, each naming its protocol:
//   whole photo  — every pixel (paper mask and table included), in the capture's sensor code
//                  values, peak = full scale: how the seed compared a real and a synthesized photo;
//   sample only  — the pixels inside the cut-out (2 px margin), same units: the honest figure for
//                  the material, far lower because the paper is easy to get right.
// Beside them the exposure-independent figures of the sample pixels, computed on linear radiance
// (the simulator's noise-free radiance of the truth against the rendering of the fit), so a dark
// view cannot score high whatever the error:
//   normalized sample PSNR — both divided by the truth's 99th percentile over the view's sample
//                  pixels (channels pooled), clamped to [0, 1], sRGB-encoded, peak 1;
//   relative RMSE — sqrt(mean (fit − truth)²) / sqrt(mean truth²) over the sample pixels.
#pragma once

#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "evaluate/image_metrics.h"
#include "geometry/rig_geometry.h"
#include "sim/scene.h"

namespace brdfrig::evaluate {

struct HeldOutView {
  std::string name;
  double phi = 0;        // light azimuth out of the camera's plane of incidence (radians)
  double elevation = 0;  // camera and light angle from the sample normal (radians)
  geometry::AxisPositions positions;
};

// Views at a fixed elevation of camera and light (mirror configuration when phi = 0), the light
// turned by phi about the sample normal. Needs the scene axes camera_arm, light_arm and
// light_azimuth (sim/scenes/default.yaml has them).
std::vector<HeldOutView> OrientationViews(double elevation, const std::vector<double>& phis);

// OrientationViews at every elevation (radians), elevation-major; names say both angles.
std::vector<HeldOutView> ElevationViews(const std::vector<double>& elevations,
                                        const std::vector<double>& phis);

struct HeldOutResult {
  HeldOutView view;
  PsnrResult whole_photo;
  PsnrResult sample_only;
  PsnrResult normalized_sample;  // exposure independent (see above)
  double relative_rmse = 0;      // sample pixels, linear radiance
  std::string relative_rmse_protocol;
  cv::Mat photo, rendering;  // sensor images (CV_32FC3, B,G,R, 1 = full scale) for reports
};

struct HeldOutOptions {
  double exposure_s = 0;       // 0: the middle exposure of the scene's bracket
  std::uint64_t frame = 1000;  // noise seed of the held-out photos (distinct from the capture)
  bool keep_images = false;
  bool linear_interpolation = false;  // slice models: the seed's linear interpolation
  void Validate() const;
};

// Renders `fitted` (GPU renderer, headless) and photographs the truth (simulator, with the
// scene's effects) for every view; needs no GL context of the caller's.
std::vector<HeldOutResult> EvaluateHeldOut(const sim::Scene& scene, const brdf::Brdf& fitted,
                                           const std::vector<HeldOutView>& views,
                                           const HeldOutOptions& options = {});

// EvaluateHeldOut for several fitted models of the same truth (e.g. every rung of the model
// ladder): each view's truth is photographed once and every model rendered against it. One
// result list per model, in the order of `fitted`.
std::vector<std::vector<HeldOutResult>> EvaluateHeldOutEach(
    const sim::Scene& scene, const std::vector<const brdf::Brdf*>& fitted,
    const std::vector<HeldOutView>& views, const HeldOutOptions& options = {});

// Bits of the capture's code values (quantization effect, 8 for JPEG, else 16 for PNG/TIFF).
int CaptureBitDepth(const sim::Scene& scene);

}  // namespace brdfrig::evaluate
