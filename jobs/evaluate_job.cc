#include "jobs/evaluate_job.h"

#include <optional>

#include "brdf/material_file.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/material_report.h"
#include "evaluate/report_json.h"
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
  if (scene) {
    say("judging: " +
        std::to_string(options.view_elevations_deg.size() * options.view_phis_deg.size()) +
        " held-out views, sphere test, BRDF error");
    evaluate::JudgeOptions judge;
    judge.view_elevations_deg = options.view_elevations_deg;
    judge.view_phis_deg = options.view_phis_deg;
    judge.held_out.keep_images = true;
    judge.held_out.linear_interpolation = options.linear_interpolation;
    judge.sphere.keep_images = true;
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

  nlohmann::json report =
      evaluate::NewReportJson("brdfrig evaluate: " + options.material.string() + " against " +
                              against + " (" + brdf::ModelKindName(material.kind) + " model)");
  report["figures"] = figures_json;
  const evaluate::WrittenReport written = evaluate::WriteReport(options.output_dir, report);
  return {written.html, written.json, written.text};
}

}  // namespace brdfrig::jobs
