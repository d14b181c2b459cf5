// `brdfrig demo`, the main job: a simulated capture of the default scene → reconstruction (every
// rung of the model ladder, one chosen by validation) → held-out renders against held-out
// photos → BRDF error against the truth (and the plan's validation photos against the fit, when
// it has them) → a report directory (report.html with plots and images, the Model ladder
// section, report.txt, material.json, hdr/, views/, the capture).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace brdfrig::jobs {

struct DemoOptions {
  std::filesystem::path scene;       // default: the built-in sim/scenes/default.yaml
  std::filesystem::path output_dir;  // the report directory
  // Held-out views: camera and light at each elevation, the light turned by each phi.
  std::vector<double> view_elevations_deg = {20, 40, 60, 75};
  std::vector<double> view_phis_deg = {0, 45, 90, 180};
  std::function<void(const std::string&)> progress;
  void Validate() const;
};

struct DemoSummary {
  std::filesystem::path report_html, report_json;
  std::string text;  // the plain-text report
};

DemoSummary RunDemo(const DemoOptions& options);

}  // namespace brdfrig::jobs
