// The figures that open a report — the material on the sphere (evaluate/material_preview.h),
// the plan's coverage in (θh, θd) (evaluate/coverage_report.h) and the BRDF's slices and albedo
// (evaluate/brdf_plots.h) — made in one call by every job that writes a report (`brdfrig demo`,
// `brdfrig evaluate`). What the job knows decides what is drawn: a truth, a glTF version, the
// capture's samples, a plan.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "evaluate/brdf_plots.h"
#include "evaluate/material_preview.h"
#include "evaluate/sphere_test.h"
#include "geometry/rig_geometry.h"

namespace brdfrig::evaluate {

// A capture plan on its rig's nominal geometry: what coverage/ maps.
struct PlanGeometry {
  std::string name;  // names the plan in the report
  geometry::RigGeometry rig;
  std::vector<geometry::AxisPositions> positions;  // radians
  std::vector<bool> validation;                    // per position
};

struct OverviewInputs {
  PreviewModels models;                 // truth (optional), fit, glTF version (optional)
  std::vector<MeasuredSample> samples;  // the fitted positions' samples (may be empty)
  std::optional<PlanGeometry> plan;     // none: no coverage section
  SphereTestOptions sphere;             // as the sphere test's, so the PSNRs agree
  BrdfPlotOptions plots;
};

// Adds "preview", "brdf_plots" and (with a plan) "coverage" to report.json's `figures`; the
// preview's images go under report_dir (none when it is empty). Throws brdfrig::Error without
// a fit, OptionsError for bad options.
void AddOverviewFigures(const OverviewInputs& inputs, const std::filesystem::path& report_dir,
                        nlohmann::json* figures);

}  // namespace brdfrig::evaluate
