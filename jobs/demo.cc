#include "jobs/demo.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "acquire/capture.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "evaluate/held_out.h"
#include "evaluate/material_overview.h"
#include "evaluate/material_report.h"
#include "evaluate/report.h"
#include "evaluate/report_json.h"
#include "jobs/ladder_section.h"
#include "jobs/report_samples.h"
#include "jobs/validation_photos.h"
#include "reconstruct/batch.h"
#include "reconstruct/gltf_export.h"
#include "sim/devices.h"
#include "sim/scene.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// rig.yaml with every device on the simulator's backend, all naming the demo's scene.
std::string SimulatedRigYaml(const fs::path& scene_file, const sim::Scene& scene) {
  const std::string at = "{backend: sim, scene: \"" + scene_file.string() + "\"}";
  std::string yaml = "geometry: \"" + scene_file.string() + "\"\ncamera: " + at + "\naxes:\n";
  for (const geometry::RotationAxis& axis : scene.rig.axes)
    yaml += "  " + axis.name + ": " + at + "\n";
  return yaml + "light: " + at + "\n";
}

// plan.yaml for the scene's capture section (angles in degrees, as people write them).
std::string PlanYaml(const sim::Scene& scene) {
  std::string yaml =
      "sample: demo\noperator: brdfrig demo\nnotes: \"" + scene.Summary() + "\"\npositions:\n";
  for (std::size_t i = 0; i < scene.capture.positions.size(); ++i) {
    std::string entry;
    for (const auto& [axis, angle] : scene.capture.positions[i]) {
      entry += (entry.empty() ? "" : ", ") + axis + ": " + Fixed(Degrees(angle), 6);
    }
    if (i < scene.capture.validation.size() && scene.capture.validation[i]) {
      entry += ", validation: true";
    }
    yaml += "  - {" + entry + "}\n";
  }
  std::string exposures;
  for (double t : scene.capture.exposures) {
    exposures += (exposures.empty() ? "" : ", ") + Fixed(t, 9);
  }
  return yaml + "exposures: [" + exposures + "]\n";
}

}  // namespace

void DemoOptions::Validate() const {
  if (output_dir.empty()) throw OptionsError("demo: no output directory given");
  if (view_phis_deg.empty()) throw OptionsError("demo: no held-out views");
  evaluate::JudgeOptions judge;
  judge.view_elevations_deg = view_elevations_deg;
  judge.view_phis_deg = view_phis_deg;
  judge.Validate();
}

DemoSummary RunDemo(const DemoOptions& options_in) {
  DemoOptions options = options_in;
  if (options.scene.empty())
    options.scene = fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml";
  options.Validate();
  const auto say = [&](const std::string& m) {
    if (options.progress) options.progress(m);
  };
  const fs::path out = options.output_dir;
  CreateDirectories(out);
  const sim::Scene scene = sim::LoadScene(options.scene);

  // 1. Capture through the acquisition engine with the simulated rig: the same plan, run
  // engine and session store a lab uses, only the devices' backend differs. A session already
  // in the directory is resumed (a finished one is left as it is).
  say("[1/4] capturing " + std::to_string(scene.capture.positions.size()) + " positions × " +
      std::to_string(scene.capture.exposures.size()) + " exposures (simulated rig)");
  auto start = std::chrono::steady_clock::now();
  sim::RegisterSimBackends();
  WriteFileAtomically(out / "rig.yaml", SimulatedRigYaml(fs::absolute(options.scene), scene));
  WriteFileAtomically(out / "plan.yaml", PlanYaml(scene));
  acquire::CaptureOptions capture_options;
  capture_options.rig_file = out / "rig.yaml";
  capture_options.plan_file = out / "plan.yaml";
  capture_options.output_dir = out / "session";
  capture_options.resume = fs::exists(out / "session" / "session.sqlite");
  int last_position = -1;
  capture_options.on_progress = [&](const acquire::RunProgress& p) {
    if (p.position == last_position || p.positions == 0) return;
    last_position = p.position;
    say("      position " + std::to_string(p.position + 1) + "/" + std::to_string(p.positions));
  };
  const acquire::CaptureSummary captured = acquire::RunCapture(capture_options);
  if (captured.run.status != acquire::ExitStatus::kSuccess) {
    throw Error("demo: the simulated capture stopped: " + captured.run.reason);
  }
  const double capture_s = SecondsSince(start);

  // 2. Reconstruct.
  say("[2/4] reconstructing");
  start = std::chrono::steady_clock::now();
  const reconstruct::CaptureSet capture = reconstruct::LoadCapture(out / "session");
  reconstruct::ReconstructOptions reconstruct_options;
  reconstruct_options.hdr_dir = out / "hdr";
  reconstruct::ReconstructionResult result = reconstruct::Reconstruct(
      capture, reconstruct_options, [&](const std::string& m) { say("      " + m); });
  result.material.provenance["input_sha256"] = reconstruct::CaptureFingerprint(capture);
  brdf::WriteMaterialFile(out / "material.json", result.material);
  // The material as glTF 2.0 beside it, for the tools people use every day (docs/gltf.md).
  const reconstruct::GltfExportSummary exported =
      reconstruct::ExportGltfFile(out / "material.json", out / "material.glb");
  say("      material.glb: " + exported.ToString());
  const double reconstruct_s = SecondsSince(start);
  const std::shared_ptr<const brdf::Brdf> fitted_model = result.material.Model();
  const brdf::Brdf& fitted = *fitted_model;

  // 3. Held-out views at every elevation, the sphere test and the BRDF-space figures.
  say("[3/4] judging the fit: " +
      std::to_string(options.view_elevations_deg.size() * options.view_phis_deg.size()) +
      " held-out views, sphere test, BRDF error");
  start = std::chrono::steady_clock::now();
  evaluate::JudgeOptions judge;
  judge.view_elevations_deg = options.view_elevations_deg;
  judge.view_phis_deg = options.view_phis_deg;
  judge.held_out.keep_images = true;
  judge.sphere.keep_images = true;
  const evaluate::MaterialFigures figures = evaluate::JudgeFit(scene, fitted, judge);
  // A plan with validation positions: its photos against the fit, as `brdfrig evaluate
  // --capture` compares them.
  std::vector<evaluate::ValidationPhotoResult> validation_photos;
  if (!result.validation.empty()) {
    say("      comparing " + std::to_string(result.validation.size()) + " validation photo(s)");
    validation_photos = CompareValidationPhotos(capture, fitted, {},
                                                [&](const std::string& m) { say("      " + m); });
  }
  // The report's opening figures: the material on a sphere beside the truth (and its glTF
  // version), the plan's coverage in (θh, θd), the BRDF's slices with the measured samples.
  say("      the material on a sphere, the plan's coverage, BRDF slices with the samples");
  evaluate::OverviewInputs opening;
  opening.models.truth = scene.sample.brdf.get();
  opening.models.fit = &fitted;
  opening.models.fit_label = std::string("fit (") + brdf::ModelKindName(result.material.kind) + ")";
  const std::shared_ptr<const brdf::Brdf> gltf =
      evaluate::GltfVersionOf(result.material, &opening.models.gltf_note);
  opening.models.gltf = gltf.get();
  if (fs::exists(out / "material.glb")) opening.models.gltf_file = "material.glb";
  opening.samples =
      MeasureReportSamples(capture, {}, [&](const std::string& m) { say("      " + m); });
  opening.plan =
      evaluate::PlanGeometry{"the demo's plan (plan.yaml, from the capture section of " +
                                 options.scene.filename().string() + ")",
                             scene.rig, scene.capture.positions, scene.capture.validation};
  opening.sphere = judge.sphere;
  nlohmann::json opening_figures = nlohmann::json::object();
  evaluate::AddOverviewFigures(opening, out, &opening_figures);
  std::vector<evaluate::ValidationPhotoResult> validation_photos_gltf;
  if (gltf && !result.validation.empty()) {
    ValidationPhotoOptions numbers_only;
    numbers_only.keep_images = false;
    validation_photos_gltf = CompareValidationPhotos(capture, *gltf, numbers_only);
  }
  const double evaluate_s = SecondsSince(start);

  say("[4/4] report");
  evaluate::Report report;
  report.title = "brdfrig demo: " + scene.Summary();
  evaluate::ReportSection overview{"Overview", {}, {}, {}, {}};
  overview.paragraphs.push_back(
      "A capture of " + options.scene.string() + " by the acquisition engine with simulated " +
      "devices (session in session/: " + std::to_string(capture.positions.size()) +
      " positions; the rig's clock says " + Fixed(captured.run.timing.session_s, 1) + " s, " +
      Fixed(captured.run.timing.Ratio(), 3) +
      "× the unavoidable moves, exposures and downloads), reconstructed into " +
      ChosenModelPhrase(result.ladder) +
      " (section Model ladder), then compared with photos of views not used for the fit "
      "(camera and light at several elevations, the light turned by phi about the sample "
      "normal), on a sphere under lights from 0° to 80° and in BRDF space" +
      (result.validation.empty() ? "" : ", and with the capture's validation photos") + ".");
  overview.tables.push_back(
      {"Wall time per step (s)",
       {"capture (simulated devices)", "reconstruction", "evaluation"},
       {{Fixed(capture_s, 1), Fixed(reconstruct_s, 1), Fixed(evaluate_s, 1)}}});
  report.sections.push_back(overview);

  evaluate::ReportSection recon{"Reconstruction", {}, {}, {}, {}};
  evaluate::Table positions{
      "Per capture position",
      {"position", "theta_in (deg)", "pose RMS (px)", "camera vs nominal (mm)", "light",
       "light vs nominal (deg)", "clipped", "samples"},
      {}};
  for (const auto& p : result.positions) {
    const bool validation =
        std::any_of(result.validation.begin(), result.validation.end(),
                    [&](const reconstruct::CapturePosition& v) { return v.index == p.index; });
    const std::string name = std::to_string(p.index) + (validation ? " (validation)" : "");
    if (!p.used) {
      positions.rows.push_back({name, "skipped: " + p.skipped_reason});
      continue;
    }
    positions.rows.push_back({name, Fixed(Degrees(p.theta_in), 2), Fixed(p.reprojection_rms_px, 3),
                              Fixed(p.camera_disagreement_m * 1000, 2),
                              p.light.from_highlight ? "highlight (refined)" : "nominal",
                              Fixed(Degrees(p.light.nominal_disagreement_rad), 3),
                              Fixed(p.invalid_fraction, 4), std::to_string(p.samples)});
  }
  recon.tables.push_back(positions);
  for (const auto& w : result.warnings) recon.paragraphs.push_back("warning: " + w);
  report.sections.push_back(recon);
  report.sections.push_back(LadderSection(result.ladder));

  nlohmann::json json = evaluate::NewReportJson(report.title);
  for (const evaluate::ReportSection& section : report.sections) {
    json["sections"].push_back(evaluate::SectionJson(section));
  }
  json["timing_s"] = {{"capture", capture_s},
                      {"reconstruction", reconstruct_s},
                      {"evaluation", evaluate_s},
                      {"rig_clock", captured.run.timing.session_s}};
  json["figures"] = evaluate::FiguresJson(figures, out);
  if (!validation_photos.empty()) {
    json["figures"]["validation_photos"] =
        evaluate::ValidationPhotosJson(validation_photos, capture.name, out);
  }
  if (!validation_photos_gltf.empty()) {
    json["figures"]["validation_photos_gltf"] =
        evaluate::ValidationPhotosJson(validation_photos_gltf, capture.name);
  }
  json["figures"].update(opening_figures);
  const evaluate::WrittenReport written = evaluate::WriteReport(out, json);
  DemoSummary summary;
  summary.text = written.text;
  summary.report_html = written.html;
  summary.report_json = written.json;
  return summary;
}

}  // namespace brdfrig::jobs
