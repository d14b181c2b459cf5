#include "jobs/evaluate_job.h"

#include <cmath>

#include "brdf/material_file.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/held_out.h"
#include "evaluate/material_report.h"
#include "evaluate/report.h"
#include "sim/scene.h"

namespace brdfrig::jobs {

void EvaluateOptions::Validate() const {
  if (material.empty()) throw OptionsError("evaluate: no material given");
  if (scene.empty()) throw OptionsError("evaluate: no scene given (--scene)");
  if (output_dir.empty()) throw OptionsError("evaluate: no output directory given (-o)");
  if (view_phis_deg.empty()) throw OptionsError("evaluate: no held-out views (--phi)");
  if (!(view_elevation_deg > 0 && view_elevation_deg < 85)) {
    throw OptionsError("evaluate: view elevation must be in (0, 85) degrees");
  }
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

  say("rendering " + std::to_string(options.view_phis_deg.size()) + " held-out views");
  std::vector<double> phis;
  for (double d : options.view_phis_deg) phis.push_back(Radians(d));
  evaluate::HeldOutOptions held_out;
  held_out.keep_images = true;
  held_out.linear_interpolation = options.linear_interpolation;
  const std::vector<evaluate::HeldOutResult> views = evaluate::EvaluateHeldOut(
      scene, fitted, evaluate::OrientationViews(Radians(options.view_elevation_deg), phis),
      held_out);

  say("BRDF error against the truth");
  evaluate::Report report;
  report.title = "brdfrig evaluate: " + options.material.string() + " against " + scene.Summary();
  report.sections.push_back(
      evaluate::HeldOutSection(views, options.view_elevation_deg, options.output_dir));
  report.sections.push_back(evaluate::BrdfSection(*scene.sample.brdf, fitted));
  report.WriteHtml(options.output_dir);
  EvaluateSummary summary;
  summary.text = report.Text();
  WriteFileAtomically(options.output_dir / "report.txt", summary.text);
  summary.report_html = options.output_dir / "report.html";
  return summary;
}

}  // namespace brdfrig::jobs
