// `brdfrig rig calibrate white`: the paper's albedo measured against a reference tile of known
// reflectance lying in the cut-out, instead of assumed. Both are Lambertian under the same lamp
// in the same photo: each pixel's linear signal, divided by the flat field's gain and by the
// irradiance the nominal geometry predicts there (cos θ / d², the lamp's intensity cancels),
// is proportional to the albedo it sees. The paper is read in a ring just outside the cut-out
// and the tile well inside it, where a pose error of a few millimetres cannot mix them.
//
// Refused: a tile that is not there (the cut-out's signal is not uniform once the irradiance is
// divided out: a glossy sample, a tile too small or tilted), photos over- or underexposed.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "calibrate/lens_calibration.h"
#include "geometry/rig_geometry.h"

namespace brdfrig::calibrate {

struct WhiteReferenceOptions {
  double reference_albedo = 0;        // the tile's certified reflectance (required)
  geometry::AxisPositions positions;  // where the arms stood (radians); default: at rest
  cv::Mat flat_field;                 // CV_32F gain map (calibrate flat); empty: none
  double inner_fraction = 0.7;        // the tile is read within this share of the cut-out
  double paper_margin_m = 0.004;      // the paper ring starts this far outside the cut-out
  double paper_ring_m = 0.02;         // and is this wide
  double max_tile_spread = 0.03;      // relative standard deviation allowed on the tile
  void Validate() const;              // throws OptionsError
};

struct WhiteReferenceResult {
  double paper_albedo = 0;
  std::vector<double> per_photo;  // the estimate from each photo
  double tile_spread = 0;         // worst relative standard deviation on the tile
  std::string ToString() const;
};

WhiteReferenceResult CalibrateWhiteReference(const std::vector<CalibrationPhoto>& photos,
                                             const geometry::RigGeometry& rig,
                                             const WhiteReferenceOptions& options);

}  // namespace brdfrig::calibrate
