// The forward model of a measured position: the HDR radiance a material predicts at the
// position's sample pixels, from the measured camera pose, light and paper radiometry. It is
// ExtractSamples' relation run the other way (HDR = f · k(x, y) · cos θ_l / d², same sample
// region, same pixel geometry), so a photo left out of the fit can be compared with the fit in
// the photo's own units (jobs/validation_photos.h).
#pragma once

#include <opencv2/core.hpp>

#include "brdf/brdf.h"
#include "geometry/rig_geometry.h"
#include "reconstruct/plane_view.h"
#include "reconstruct/radiometry.h"
#include "reconstruct/samples.h"

namespace brdfrig::reconstruct {

struct PredictedSample {
  cv::Mat radiance;  // CV_32FC3, B,G,R, the photo's HDR units; 0 outside the mask
  cv::Mat mask;      // CV_8UC1, 255 at the sample pixels that are valid in the photo
};

// `valid`: the photo's HDR validity (pixels clipped in every exposure are left out, as the
// samples leave them out).
PredictedSample PredictSampleRadiance(const brdf::Brdf& material, const cv::Mat& valid,
                                      const PlaneView& view, const geometry::Vec3& light,
                                      const Radiometry& radiometry,
                                      const geometry::TargetGeometry& target,
                                      const SampleOptions& options);

}  // namespace brdfrig::reconstruct
