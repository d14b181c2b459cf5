// `brdfrig evaluate`: a fitted material against a simulated scene's truth — held-out views
// (light turned by phi about the normal, PSNR whole-photo and sample-only) and the BRDF-space
// error — written as a report directory (report.html, report.txt, views/).
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
  double view_elevation_deg = 40;
  std::vector<double> view_phis_deg = {0, 20, 45, 90, 135, 180};
  bool linear_interpolation = false;  // render the slice model as the seed did
  std::function<void(const std::string&)> progress;
  void Validate() const;
};

struct EvaluateSummary {
  std::filesystem::path report_html;
  std::string text;
};

EvaluateSummary RunEvaluate(const EvaluateOptions& options);

}  // namespace brdfrig::jobs
