// The figures that judge a fitted material against a simulated truth, shared by `brdfrig demo`,
// `brdfrig evaluate` and the studies: held-out photo views at several elevations, the sphere
// test and the BRDF-space figures. They go into report.json (the source of report.html and the
// text summary, evaluate/report_json.h) under "figures".
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "brdf/brdf.h"
#include "evaluate/brdf_figures.h"
#include "evaluate/held_out.h"
#include "evaluate/sphere_test.h"
#include "sim/scene.h"

namespace brdfrig::evaluate {

struct MaterialFigures {
  std::vector<HeldOutResult> held_out;
  SphereTestResult sphere;
  BrdfFigures brdf;
};

// The summary of the held-out views at one elevation (means over its light azimuths).
struct ElevationSummary {
  double elevation_deg = 0;
  int views = 0;
  double whole_photo_psnr_db = 0, sample_only_psnr_db = 0, normalized_sample_psnr_db = 0;
  int normalized_views = 0;  // views with a defined normalized figure (the truth not black)
  double relative_rmse = 0;
};
std::vector<ElevationSummary> SummarizeByElevation(const std::vector<HeldOutResult>& views);

// What a fit is judged on: held-out views at every elevation × light azimuth, the sphere test
// and the BRDF-space figures.
struct JudgeOptions {
  std::vector<double> view_elevations_deg = {20, 40, 60, 75};  // camera and light, from normal
  std::vector<double> view_phis_deg = {0, 45, 90, 180};        // light azimuth out of plane
  HeldOutOptions held_out;
  SphereTestOptions sphere;
  BrdfFiguresOptions brdf;
  void Validate() const;  // throws OptionsError
  // The held-out views: every elevation × light azimuth (ElevationViews), elevation-major.
  std::vector<HeldOutView> Views() const;
};

// Every figure of `fitted` against the scene's sample (its truth). Held-out views need a GL
// context of their own (headless) and the scene axes of OrientationViews.
MaterialFigures JudgeFit(const sim::Scene& scene, const brdf::Brdf& fitted,
                         const JudgeOptions& options = {});

// JudgeFit for several fits of the same truth (every rung of the model ladder): the held-out
// truth is photographed once per view. One MaterialFigures per fit, in order.
std::vector<MaterialFigures> JudgeFitEach(const sim::Scene& scene,
                                          const std::vector<const brdf::Brdf*>& fitted,
                                          const JudgeOptions& options = {});

// Sphere test and BRDF figures (the CPU part; held-out views need the simulator and GL).
MaterialFigures JudgeBrdf(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                          const SphereTestOptions& sphere = {},
                          const BrdfFiguresOptions& brdf = {});

// The figures as report.json's "figures" object. With a non-empty `report_dir`, the images the
// results kept (held-out photo / rendering / difference, sphere truth / fit) are written under
// it (views/, spheres/) and named in the json relative to it.
nlohmann::json FiguresJson(const MaterialFigures& figures,
                           const std::filesystem::path& report_dir = {});

// Numbers in report.json: finite values as numbers, others as "inf", "-inf" or "nan" (JSON
// has no infinity, and an identical fit has an infinite PSNR).
nlohmann::json JsonNumber(double value);
double NumberFromJson(const nlohmann::json& value);

}  // namespace brdfrig::evaluate
