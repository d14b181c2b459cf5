// Validation photos of a capture (simulated or hardware) against the fitted material: each
// photo's HDR radiance over its sample pixels compared with what the material predicts under
// the geometry measured from that photo (jobs/validation_photos.h measures and predicts). The
// figures are sample_figures.h's, with the photo as the reference. They go into report.json
// under "figures": {"validation_photos": {...}}; report_json.cc makes the section from there.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "evaluate/report.h"
#include "evaluate/sample_figures.h"

namespace brdfrig::evaluate {

struct ValidationPhotoResult {
  int position = 0;       // capture position index
  bool measured = false;  // false: the photo could not be measured (reason in `error`)
  std::string error;
  double theta_in_deg = 0;  // incidence angle at the cut-out's centre (measured)
  std::string light;        // where its light came from: LightEstimate::Source()
  SampleFigures figures;
  // HDR radiance (CV_32FC3, B,G,R) of the photo and the prediction, cropped to the sample
  // pixels' bounding box, zero outside them; for the report's images.
  cv::Mat photo, prediction;
};

// report.json's "validation_photos" object: the capture, the material, the protocols and one
// entry per position. With a non-empty `report_dir`, photo / prediction / |difference| images
// are written under report_dir/validation/ (same display scale) and named relative to it.
nlohmann::json ValidationPhotosJson(const std::vector<ValidationPhotoResult>& results,
                                    const std::string& capture_name,
                                    const std::filesystem::path& report_dir = {});

// The report's section made from that object.
ReportSection ValidationPhotosSection(const nlohmann::json& validation_photos);

}  // namespace brdfrig::evaluate
