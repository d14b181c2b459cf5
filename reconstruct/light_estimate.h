// The light's position from the highlight on the sample. The highlight marks the mirror point:
// the ray from the camera through it, reflected about the sample normal, points at the light.
// The direction is measured; the distance along it is taken from the rig's nominal light (one
// highlight cannot tell it). When there is no usable highlight (a matte sample, the highlight
// outside the cut-out or at its edge), the nominal light is used and a warning says so. So it is
// when the peak found would put the light further from the rig's nominal light than a rig is
// ever off (`max_nominal_disagreement_deg`): far from the mirror configuration a photo's
// brightest spot is the lobe's tail or Fresnel rising towards one side, not a mirror highlight,
// and taking it for one moved the light by 56° (nickel, the designed plan's large-θh photo at
// 1600×1200).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"
#include "reconstruct/plane_view.h"

namespace brdfrig::reconstruct {

struct LightOptions {
  // false: the rig's light is calibrated (geometry/light_calibration_file.h) and taken as it is;
  // a highlight can only add its own error to a measured position.
  bool use_highlight = true;
  double smoothing_px = 1.5;    // Gaussian sigma before the peak search (noise)
  double min_peak_ratio = 2.0;  // peak / median luminance in the cut-out below which there is
                                // no highlight to speak of
  double edge_inset = 0.03;     // fraction of the cut-out's size ignored along its border
  // Largest angle (at the highlight) between the measured and the nominal light direction for
  // the peak to count as the mirror highlight; a rig that is off by more needs its rig file
  // fixed, which the warning says.
  double max_nominal_disagreement_deg = 10;
  void Validate() const;
};

struct LightEstimate {
  geometry::Vec3 position = geometry::Vec3::Zero();  // world, metres
  bool from_highlight = false;                       // false: the nominal light was used
  bool from_calibration = false;  // the rig's calibrated light (LightOptions::use_highlight off)
  bool saturated_peak = false;    // the highlight is clipped in every exposure
  cv::Point2d highlight_px{-1, -1};
  geometry::Vec3 highlight_in_world = geometry::Vec3::Zero();
  double nominal_disagreement_rad = 0;  // angle between measured and nominal light directions
  std::vector<std::string> warnings;
  // "calibration", "highlight" or "nominal": for material.json's provenance.
  const char* Source() const;
};

LightEstimate EstimateLight(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                            const geometry::TargetGeometry& target,
                            const geometry::Vec3& nominal_light, const LightOptions& options);

}  // namespace brdfrig::reconstruct
