// A capture's validation photos against a fitted material, the same code for simulated and
// hardware captures: each chosen position is measured as the reconstruction measures it
// (reconstruct::MeasurePosition: HDR merge → cut-out pose → light from the highlight → paper
// radiometry), the material is evaluated at every sample pixel under that measured geometry
// (reconstruct::PredictSampleRadiance) and compared with the photo's HDR radiance
// (evaluate::CompareSampleRadiance, the photo as the reference).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "evaluate/validation_photos.h"
#include "reconstruct/capture_set.h"
#include "reconstruct/measure_position.h"

namespace brdfrig::jobs {

struct ValidationPhotoOptions {
  // Capture position indices to compare; empty = the plan's validation positions.
  std::vector<int> positions;
  reconstruct::MeasureOptions measure;  // as the reconstruction's defaults
  bool keep_images = true;              // the cropped photo and prediction, for reports
  void Validate() const;
};

// The positions compared: `options.positions`, else the capture's validation positions.
// Throws OptionsError naming the capture when there are none, or when a named position is not
// in the capture (listing the ones that are).
std::vector<int> ValidationPositionsOf(const reconstruct::CaptureSet& capture,
                                       const ValidationPhotoOptions& options);

// One result per position, in capture order; a position that cannot be measured is reported
// (measured = false) with the reason. Throws brdfrig::Error when none can be measured.
std::vector<evaluate::ValidationPhotoResult> CompareValidationPhotos(
    const reconstruct::CaptureSet& capture, const brdf::Brdf& material,
    const ValidationPhotoOptions& options, const std::function<void(const std::string&)>& say = {});

}  // namespace brdfrig::jobs
