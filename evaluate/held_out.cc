#include "evaluate/held_out.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "common/angles.h"
#include "common/error.h"
#include "common/option_check.h"
#include "evaluate/sample_figures.h"
#include "render/capture_view.h"
#include "render/gl_context.h"
#include "sim/simulator.h"

namespace brdfrig::evaluate {
namespace {

// Pixels inside the cut-out as the true camera sees it, shrunk by `margin` pixels so edge
// pixels (part paper, part sample) do not count as sample.
cv::Mat SampleMask(const sim::TrueGeometry& g, const geometry::TargetGeometry& target, int margin) {
  cv::Mat mask(g.intrinsics.height, g.intrinsics.width, CV_8UC1, cv::Scalar(0));
  const double w = target.cutout_width / 2, h = target.cutout_height / 2;
  std::vector<cv::Point> corners;
  for (const auto& [x, y] : {std::pair{-w, -h}, {w, -h}, {w, h}, {-w, h}}) {
    Eigen::Vector2d px;
    if (!geometry::ProjectToPixel(g.intrinsics, g.camera, {x, y, 0}, &px)) return mask;
    corners.emplace_back(static_cast<int>(std::lround(px.x())),
                         static_cast<int>(std::lround(px.y())));
  }
  cv::fillConvexPoly(mask, corners, cv::Scalar(255));
  if (margin > 0) {
    cv::erode(mask, mask,
              cv::getStructuringElement(cv::MORPH_RECT, {2 * margin + 1, 2 * margin + 1}));
  }
  return mask;
}

std::string Protocol(const char* region, int bits) {
  std::ostringstream out;
  out << region << ", " << bits << "-bit sensor code values, peak = full scale";
  return out.str();
}

}  // namespace

std::vector<HeldOutView> ElevationViews(const std::vector<double>& elevations,
                                        const std::vector<double>& phis) {
  std::vector<HeldOutView> views;
  for (double elevation : elevations) {
    for (HeldOutView v : OrientationViews(elevation, phis)) {
      v.name = "el=" + std::to_string(std::lround(elevation * 180 / M_PI)) + "deg " + v.name;
      views.push_back(std::move(v));
    }
  }
  return views;
}

std::vector<HeldOutView> OrientationViews(double elevation, const std::vector<double>& phis) {
  std::vector<HeldOutView> views;
  for (double phi : phis) {
    std::ostringstream name;
    name << "phi=" << std::lround(Degrees(phi)) << "deg";
    views.push_back(
        {name.str(),
         phi,
         elevation,
         {{"camera_arm", elevation}, {"light_arm", -elevation}, {"light_azimuth", phi}}});
  }
  return views;
}

void HeldOutOptions::Validate() const {
  CheckOption(exposure_s >= 0, "HeldOutOptions.exposure_s", exposure_s,
              ">= 0 (0 = the bracket's middle)");
}

int CaptureBitDepth(const sim::Scene& scene) {
  if (scene.effects.quantization) return scene.effects.quantization->bits;
  return scene.sensor.format == sim::PhotoFormat::kJpeg8 ? 8 : 16;
}

std::vector<HeldOutResult> EvaluateHeldOut(const sim::Scene& scene, const brdf::Brdf& fitted,
                                           const std::vector<HeldOutView>& views,
                                           const HeldOutOptions& options) {
  return std::move(EvaluateHeldOutEach(scene, {&fitted}, views, options).front());
}

std::vector<std::vector<HeldOutResult>> EvaluateHeldOutEach(
    const sim::Scene& scene, const std::vector<const brdf::Brdf*>& fitted,
    const std::vector<HeldOutView>& views, const HeldOutOptions& options) {
  options.Validate();
  double exposure = options.exposure_s;
  if (exposure == 0) {
    if (scene.capture.exposures.empty()) throw Error("held-out: the scene has no exposures");
    exposure = scene.capture.exposures[scene.capture.exposures.size() / 2];
  }
  const sim::Simulator truth(scene);
  // The rendering goes through the same sensor, without the noise (a rendering has none).
  sim::Scene noiseless = scene;
  noiseless.effects.shot_noise.reset();
  noiseless.effects.read_noise.reset();
  const sim::Simulator sensor(noiseless);
  const int bits = CaptureBitDepth(scene);

  const auto context = render::CreateHeadlessContext();
  std::vector<std::vector<HeldOutResult>> results(fitted.size());
  for (const HeldOutView& view : views) {
    const sim::TrueGeometry g = truth.GeometryAt(view.positions);
    const cv::Mat true_radiance = truth.RenderRadiance(view.positions);
    cv::Mat photo = truth.Expose(true_radiance, exposure, options.frame);
    // Code values as the photo file holds them: clamp to the sensor's range.
    cv::min(cv::max(photo, 0.0), 1.0, photo);
    const cv::Mat mask = SampleMask(g, scene.rig.target, 2);
    render::CaptureView capture;
    capture.target = scene.rig.target;
    capture.background_albedo = scene.background_albedo;
    capture.view = {g.intrinsics, g.camera};
    capture.light = {g.light_position, brdf::Rgb::Constant(g.light_intensity)};
    capture.supersampling = scene.render.supersampling;
    capture.linear_interpolation = options.linear_interpolation;
    for (std::size_t m = 0; m < fitted.size(); ++m) {
      HeldOutResult r;
      r.view = view;
      const cv::Mat fitted_radiance = render::RenderCaptureView(capture, *fitted[m]);
      cv::Mat rendering = sensor.Expose(fitted_radiance, exposure, options.frame);
      cv::min(cv::max(rendering, 0.0), 1.0, rendering);
      r.whole_photo = Psnr(photo, rendering, cv::Mat(), 1.0, Protocol("whole photo", bits));
      r.sample_only = Psnr(photo, rendering, mask, 1.0, Protocol("sample only", bits));
      const SampleFigures figures =
          CompareSampleRadiance(true_radiance, fitted_radiance, mask, "truth");
      r.normalized_sample = figures.normalized_sample;
      r.relative_rmse = figures.relative_rmse;
      r.relative_rmse_protocol = figures.relative_rmse_protocol;
      if (options.keep_images) {
        r.photo = photo;
        r.rendering = rendering;
      }
      results[m].push_back(std::move(r));
    }
  }
  return results;
}

}  // namespace brdfrig::evaluate
