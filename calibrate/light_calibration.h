// `brdfrig rig calibrate light`: where the light stands, from the highlights of a mirror tile
// (polished black glass, a front-surface mirror) lying flat in the cut-out. In each photo the
// highlight's centre is the mirror point: the camera's ray through it, reflected about the
// sample plane, passes through the light. The axes carry the light from its rest position by a
// known rigid motion (RigGeometry::LightMotion), so every photo's reflected ray is a linear
// constraint on the one rest position, which least squares triangulates.
//
// All the reflected rays leave the cut-out, so the triangulation's baseline is the cut-out's
// size: spread the mirror points over it (docs/calibration.md suggests positions). `dilution`
// says how much less certain the light is than one ray; past `max_dilution` the photos cannot
// tell the light's distance and the calibration is refused.
//
// Refused: no highlight in the cut-out (no tile, a matte tile, the light off), a highlight at the
// cut-out's edge (the mirror point may be outside), photos of another camera, fewer than
// `min_photos` photos, rays that cannot locate the light, and photos that disagree (a ray
// missing the fitted light by more than `max_miss_m`: a tilted tile, positions out of order).
#pragma once

#include <string>
#include <vector>

#include "calibrate/lens_calibration.h"
#include "geometry/rig_geometry.h"

namespace brdfrig::calibrate {

struct LightPhoto {
  CalibrationPhoto photo;
  geometry::AxisPositions positions;  // where the axes stood (radians)
};

struct LightCalibrationOptions {
  int min_photos = 3;
  double smoothing_px = 1.0;   // Gaussian sigma before the peak search (noise)
  double min_peak_ratio = 10;  // peak / median in the cut-out: below it, no mirror highlight
  double edge_inset = 0.05;    // share of the cut-out's size ignored along its border
  double max_dilution = 25;    // the light at most this many times less certain than a ray
  double max_miss_m = 0.002;   // largest distance of the fitted light from a photo's ray
  void Validate() const;       // throws OptionsError
};

struct LightPhotoResult {
  std::string name;
  double highlight_x = 0, highlight_y = 0;  // pixels
  double miss_m = 0;                        // distance of the fitted light from its ray
};

struct LightCalibrationResult {
  geometry::Vec3 light_position = geometry::Vec3::Zero();  // at rest (world, metres)
  double nominal_offset_m = 0;                             // from the rig's nominal rest position
  double rms_miss_m = 0;
  double dilution = 0;
  std::vector<LightPhotoResult> photos;
  std::string ToString() const;
};

// `rig` is what the lab believes about the camera and the axes (its lens calibration applied);
// its light position is only compared with the result.
LightCalibrationResult CalibrateLight(const std::vector<LightPhoto>& photos,
                                      const geometry::RigGeometry& rig,
                                      const LightCalibrationOptions& options);

}  // namespace brdfrig::calibrate
