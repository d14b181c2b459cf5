#include "jobs/evaluate_job.h"

#include <optional>

#include "brdf/material_file.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/material_overview.h"
#include "evaluate/material_report.h"
#include "evaluate/report_json.h"
#include "jobs/report_samples.h"
#include "jobs/validation_photos.h"
#include "reconstruct/batch.h"
#include "sim/scene.h"

namespace brdfrig::jobs {

void EvaluateOptions::Validate() const {
  if (material.empty()) throw OptionsError("evaluate: no material given");
  if (scene.empty() && capture.empty()) {
    throw OptionsError(
        "evaluate: no truth given: a simulated scene (--scene) or a capture with validation "
        "photos (--capture)");
  }
  if (!positions.empty() && capture.empty()) {
    throw OptionsError("evaluate: positions are named (--positions) but no capture (--capture)");
  }
  if (output_dir.empty()) throw OptionsError("evaluate: no output directory given (-o)");
  if (view_phis_deg.empty()) throw OptionsError("evaluate: no held-out views (--phi)");
  evaluate::JudgeOptions judge;
  judge.view_elevations_deg = view_elevations_deg;
  judge.view_phis_deg = view_phis_deg;
  judge.Validate();
}

EvaluateSummary RunEvaluate(const EvaluateOptions& options) {
  options.Validate();
  const auto say = [&](const std::string& m) {
    if (options.progress) options.progress(m);
  };
  const brdf::Material material = brdf::ReadMaterialFile(options.material);
  const std::shared_ptr<const brdf::Brdf> fitted_model = material.Model();
  const brdf::Brdf& fitted = *fitted_model;
  // Everything read and checked before the report directory is made: a wrong input leaves
  // nothing behind.
  std::optional<sim::Scene> scene;
  if (!options.scene.empty()) scene = sim::LoadScene(options.scene);
  std::optional<reconstruct::CaptureSet> capture;
  ValidationPhotoOptions photo_options;
  photo_options.positions = options.positions;
  if (!options.capture.empty()) {
    capture = reconstruct::LoadCapture(options.capture);
    (void)ValidationPositionsOf(*capture, photo_options);
  }
  CreateDirectories(options.output_dir);

  std::string against;
  nlohmann::json figures_json = nlohmann::json::object();
  evaluate::JudgeOptions judge;
  judge.view_elevations_deg = options.view_elevations_deg;
  judge.view_phis_deg = options.view_phis_deg;
  judge.held_out.keep_images = true;
  judge.held_out.linear_interpolation = options.linear_interpolation;
  judge.sphere.keep_images = true;
  if (scene) {
    say("judging: " +
        std::to_string(options.view_elevations_deg.size() * options.view_phis_deg.size()) +
        " held-out views, sphere test, BRDF error");
    const evaluate::MaterialFigures figures = evaluate::JudgeFit(*scene, fitted, judge);
    figures_json = evaluate::FiguresJson(figures, options.output_dir);
    against = scene->Summary();
  }
  if (capture) {
    const std::vector<evaluate::ValidationPhotoResult> photos =
        CompareValidationPhotos(*capture, fitted, photo_options, say);
    figures_json["validation_photos"] =
        evaluate::ValidationPhotosJson(photos, capture->name, options.output_dir);
    against += (against.empty() ? "" : " and ") + ("the photos of " + capture->name);
  }

  // The report's opening figures: the material on a sphere (beside the truth, or beside the
  // validation photos), its glTF version, the plan's coverage, BRDF slices and albedo.
  evaluate::OverviewInputs overview;
  overview.models.truth = scene ? scene->sample.brdf.get() : nullptr;
  overview.models.fit = &fitted;
  overview.models.fit_label = std::string("fit (") + brdf::ModelKindName(material.kind) + ")";
  const std::shared_ptr<const brdf::Brdf> gltf =
      evaluate::GltfVersionOf(material, &overview.models.gltf_note);
  overview.models.gltf = gltf.get();
  overview.sphere = judge.sphere;
  if (capture) {
    say("measuring the capture's fitted positions for the BRDF slices' samples");
    overview.samples = MeasureReportSamples(*capture, photo_options.measure, say);
    evaluate::PlanGeometry plan{
        "the plan of " + capture->name + " (its recorded axis readings)", capture->nominal, {}, {}};
    for (const reconstruct::CapturePosition& p : capture->positions) {
      plan.positions.push_back(p.axis_readings);
      plan.validation.push_back(p.validation);
    }
    overview.plan = plan;
    if (gltf) {
      ValidationPhotoOptions numbers_only = photo_options;
      numbers_only.keep_images = false;
      figures_json["validation_photos_gltf"] = evaluate::ValidationPhotosJson(
          CompareValidationPhotos(*capture, *gltf, numbers_only, say), capture->name);
    }
  } else if (scene) {
    overview.plan =
        evaluate::PlanGeometry{"the capture plan of " + options.scene.string(), scene->rig,
                               scene->capture.positions, scene->capture.validation};
  }
  evaluate::AddOverviewFigures(overview, options.output_dir, &figures_json);

  nlohmann::json report =
      evaluate::NewReportJson("brdfrig evaluate: " + options.material.string() + " against " +
                              against + " (" + brdf::ModelKindName(material.kind) + " model)");
  report["figures"] = figures_json;
  const evaluate::WrittenReport written = evaluate::WriteReport(options.output_dir, report);
  return {written.html, written.json, written.text};
}

}  // namespace brdfrig::jobs
