// `brdfrig evaluate`: a fitted material against a simulated scene's truth — held-out views at
// several elevations (light turned by phi about the normal; PSNR whole photo, sample only and
// normalized, relative RMSE), the sphere test and the BRDF-space figures — written as a report
// directory (report.json with every figure, report.html and report.txt from it, views/,
// spheres/).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace brdfrig::jobs {

struct EvaluateOptions {
  std::filesystem::path material;    // material.json to judge
  std::filesystem::path scene;       // the scene whose sample is the truth
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
