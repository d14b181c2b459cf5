// `brdfrig evaluate`: a fitted material judged against a truth, written as a report directory
// (report.json with every figure, report.html and report.txt from it, images beside them).
// Two truths, either or both:
//   a simulated scene (--scene) — held-out views at several elevations (light turned by phi
//     about the normal; PSNR whole photo, sample only and normalized, relative RMSE), the sphere
//     test and the BRDF-space figures (views/, spheres/);
//   a capture (--capture, a session or `brdfrig simulate` output, simulated or hardware alike)
//     — its validation photos (or the positions named) against the material under the
//     geometry measured from each photo (jobs/validation_photos.h; validation/).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace brdfrig::jobs {

struct EvaluateOptions {
  std::filesystem::path material;    // material.json to judge
  std::filesystem::path scene;       // the scene whose sample is the truth (optional)
  std::filesystem::path capture;     // a capture whose validation photos are the truth (optional)
  std::vector<int> positions;        // capture positions to compare; empty = plan's validation
  std::filesystem::path output_dir;  // the report directory
  std::vector<double> view_elevations_deg = {20, 40, 60, 75};
  std::vector<double> view_phis_deg = {0, 45, 90, 180};
  bool linear_interpolation = false;  // render the slice model as the seed did
  std::function<void(const std::string&)> progress;
  void Validate() const;
};

struct EvaluateSummary {
  std::filesystem::path report_html, report_json;
  std::string text;
};

EvaluateSummary RunEvaluate(const EvaluateOptions& options);

}  // namespace brdfrig::jobs
