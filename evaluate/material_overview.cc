#include "evaluate/material_overview.h"

#include "common/check.h"
#include "common/error.h"
#include "coverage/coverage.h"
#include "evaluate/coverage_report.h"

namespace brdfrig::evaluate {

void AddOverviewFigures(const OverviewInputs& in, const std::filesystem::path& report_dir,
                        nlohmann::json* figures) {
  BRDFRIG_CHECK(figures != nullptr, "AddOverviewFigures needs the figures object");
  if (in.models.fit == nullptr) throw Error("report: no fitted material to show");
  (*figures)["preview"] = MaterialPreviewJson(in.models, in.sphere, report_dir);
  if (in.plan) {
    (*figures)["coverage"] = CoverageJson(
        coverage::ComputeCoverage(in.plan->rig, in.plan->positions, in.plan->validation),
        in.plan->name);
  }
  std::vector<PlotModel> models;
  if (in.models.truth) models.push_back({"truth", "truth", in.models.truth});
  models.push_back(
      {"fit", in.models.fit_label.empty() ? "fit" : in.models.fit_label, in.models.fit});
  if (in.models.gltf) models.push_back({"gltf", "glTF version", in.models.gltf});
  (*figures)["brdf_plots"] = BrdfPlotsJson(ComputeBrdfPlots(models, in.samples, in.plots));
}

}  // namespace brdfrig::evaluate
