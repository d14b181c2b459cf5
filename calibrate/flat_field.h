// `brdfrig rig calibrate flat`: the camera's relative gain across the frame (vignetting) from
// photos of a uniformly radiant card filling the frame (a diffuser in front of the lens, or a
// matte card under even light). The photos are averaged and a smooth surface (a polynomial in
// the image coordinates) fitted, so noise and dust do not enter the map; the map is scaled to
// mean 1 (its absolute level is the white reference's business).
//
// Refused: overexposed or underexposed photos, photos of different sizes, and a card that is
// not uniform (the smooth fit leaves more than `max_fit_rms` of the signal).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "calibrate/lens_calibration.h"

namespace brdfrig::calibrate {

struct FlatFieldOptions {
  int degree = 6;              // of the polynomial surface in x and y
  double min_signal = 0.05;    // median signal, share of full scale
  double max_clipped = 0.001;  // share of pixels at full scale
  double max_fit_rms = 0.02;   // relative RMS of the photos about the fitted surface
  int stride = 8;              // the fit uses every stride-th pixel in x and y
  void Validate() const;       // throws OptionsError
};

struct FlatFieldResult {
  cv::Mat gain;  // CV_32F, the photos' size, mean 1
  int photos = 0;
  double fit_rms = 0;  // relative RMS about the fitted surface (noise + non-uniformity)
  double min_gain = 0, max_gain = 0;
  std::string ToString() const;
};

// Photos are linear (RAW-like PNG/TIFF, or the simulator's): an in-camera tone curve would
// bend the map.
FlatFieldResult CalibrateFlatField(const std::vector<CalibrationPhoto>& photos,
                                   const FlatFieldOptions& options);

// Writes the gain map as an EXR (the map in every channel) and FILE.json beside it with the
// statistics and the photos used.
void WriteFlatField(const std::string& path, const FlatFieldResult& result,
                    const std::vector<CalibrationPhoto>& photos);

}  // namespace brdfrig::calibrate
