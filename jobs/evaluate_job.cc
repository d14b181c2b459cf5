#include "jobs/evaluate_job.h"

#include "brdf/material_file.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/material_report.h"
#include "evaluate/report_json.h"
#include "sim/scene.h"

namespace brdfrig::jobs {

void EvaluateOptions::Validate() const {
  if (material.empty()) throw OptionsError("evaluate: no material given");
  if (scene.empty()) throw OptionsError("evaluate: no scene given (--scene)");
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
  const sim::Scene scene = sim::LoadScene(options.scene);
  std::filesystem::create_directories(options.output_dir);

  say("judging: " +
      std::to_string(options.view_elevations_deg.size() * options.view_phis_deg.size()) +
      " held-out views, sphere test, BRDF error");
  evaluate::JudgeOptions judge;
  judge.view_elevations_deg = options.view_elevations_deg;
  judge.view_phis_deg = options.view_phis_deg;
  judge.held_out.keep_images = true;
  judge.held_out.linear_interpolation = options.linear_interpolation;
  judge.sphere.keep_images = true;
  const evaluate::MaterialFigures figures = evaluate::JudgeFit(scene, fitted, judge);

  nlohmann::json report = evaluate::NewReportJson("brdfrig evaluate: " + options.material.string() +
                                                  " against " + scene.Summary());
  report["figures"] = evaluate::FiguresJson(figures, options.output_dir);
  const evaluate::WrittenReport written = evaluate::WriteReport(options.output_dir, report);
  return {written.html, written.json, written.text};
}

}  // namespace brdfrig::jobs
