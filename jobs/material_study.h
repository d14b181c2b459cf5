// The hemisphere study: for each sample material (analytic or measured), a simulated capture
// on a plan, the reconstruction, and every figure of evaluate/material_report.h. Materials are
// scene `sample.brdf` snippets, so a measured one is `{model: nbrdf, name: <material>}` and
// adding a set is adding lines; plans are explicit position lists, so a designed plan plugs in.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "evaluate/material_report.h"
#include "geometry/rig_geometry.h"
#include "jobs/study.h"
#include "prior/build_prior.h"

namespace brdfrig::jobs {

struct StudyMaterial {
  std::string name;       // table row name
  std::string brdf_yaml;  // the scene's sample.brdf in YAML flow syntax
};

// GGX, Beckmann (Cook–Torrance), Ward and Lambert + Blinn–Phong at several roughnesses.
std::vector<StudyMaterial> AnalyticStudyMaterials();

// One `{model: nbrdf, name: <stem>}` per *.json file in `dir` (sorted by name); empty when the
// directory does not exist.
std::vector<StudyMaterial> MeasuredStudyMaterials(const std::filesystem::path& dir);

struct StudyPlan {
  std::string name;
  std::vector<geometry::AxisPositions> positions;  // axis values in radians
};

// Today's default: 6 mirror configurations, symmetric arms at 15°, 25°, …, 65°.
StudyPlan MirrorPlan();

// The plan designer's choice (coverage::DesignPlan, default options) of `count` fitted
// positions for the rig of `scene` (default: sim/scenes/default.yaml); no validation positions.
StudyPlan DesignedPlan(int count, const std::filesystem::path& scene = {});

struct MaterialStudyOptions {
  std::filesystem::path scene;  // base scene (default: sim/scenes/default.yaml)
  int width = 400, height = 300;
  int supersampling = 1;
  evaluate::JudgeOptions judge;    // the figures (elevations, lights, albedo angles)
  std::filesystem::path work_dir;  // scratch; one subdirectory per material
  std::string model;  // ladder rung to force ("seed", ...); empty: every rung, chosen by validation
  bool every_rung = false;  // judge every fitted rung (MaterialStudyRow::rungs)
  bool brdf_only = false;   // sphere test and BRDF figures only (no held-out views, no GL)
  // The measured prior for a material (nullptr or empty: the shipped prior). Studies of the
  // shipped measured materials pass the prior built without the material.
  std::function<const prior::MeasuredPrior*(const StudyMaterial&)> prior_for;
  // When set, each material's reconstructed material.json is kept as
  // keep_materials_dir/<FileStem(name)>.json.
  std::filesystem::path keep_materials_dir;
  // A departed rig, the lab's belief and its calibrations (StudySettings has the same).
  std::function<void(sim::Scene*)> depart;
  std::optional<geometry::RigGeometry> believed_rig;
  geometry::RigCalibrationFiles calibration;
  void Validate() const;  // throws OptionsError
};

// Judges a shipped measured material by a prior that was never trained on it: the shipped
// prior's settings rebuilt from every shipped material but that one, on first use and kept.
// For MaterialStudyOptions::prior_for; safe to call from several threads (a study that
// judges materials in parallel), each prior built once.
class LeaveOneOutPriors {
 public:
  // nullptr for a material that is not in the training set: the shipped prior never saw it.
  const prior::MeasuredPrior* For(const StudyMaterial& material);

 private:
  std::mutex mutex_;
  std::optional<prior::TrainingSet> training_;
  std::map<std::string, prior::MeasuredPrior> built_;
};

// One rung's headline figures (same protocols as the row's).
struct RungRow {
  std::string kind;
  bool fitted = false;
  std::string error;
  bool chosen = false;  // validation's choice
  double validation_score = 0;
  double sphere_mean_db = 0, sphere_worst_db = 0, sphere_worst_light_deg = 0;
  double held_out_mean_db = 0, held_out_min_db = 0;  // NaN with brdf_only
  std::string held_out_worst_view;                   // the view of held_out_min_db
  double albedo_error_0_75 = 0;
  double brdf_error = 0;
  double fit_s = 0;
  std::size_t size_bytes = 0;
};

struct MaterialStudyRow {
  StudyMaterial material;
  std::string error;  // non-empty: the point failed (capture, reconstruction or evaluation)
  StudyResult result;
  double wall_s = 0;
  // Headline figures (from result.figures).
  double sphere_mean_db = 0, sphere_worst_db = 0;
  double held_out_mean_db = 0, held_out_min_db = 0;  // normalized sample PSNR over the views
  int held_out_views = 0;  // views with a defined figure (the truth not black over the sample)
  double albedo_error_0_75 = 0;  // max relative error, 0°..75°
  // With MaterialStudyOptions::every_rung: every rung (the headline figures above are the
  // chosen rung's), the index of validation's choice and of the best rung by sphere mean.
  std::vector<RungRow> rungs;
  int chosen = -1, best = -1;
  // The written material's glTF version on the same sphere test against the truth (NaN when
  // reconstruct wrote none), and the export's own loss reconstruct recorded: the glTF version
  // against the chosen rung (material.json's gltf_fit.sphere_vs_model).
  double gltf_sphere_mean_db = NAN, gltf_sphere_worst_db = NAN;
  double gltf_vs_rung_db = NAN;
  std::string Report() const;  // one line (per rung with every_rung)
};

// A study material's name as a file stem: letters, digits, '-' and '.' kept, anything else '_'.
std::string FileStem(const std::string& name);

MaterialStudyRow RunMaterialStudyPoint(const StudyMaterial& material, const StudyPlan& plan,
                                       const MaterialStudyOptions& options);

// Mean and worst (lowest PSNR / highest error) over the rows that succeeded.
struct MaterialStudySummary {
  int materials = 0, failed = 0;
  double sphere_mean_db = 0, held_out_mean_db = 0, albedo_error_mean = 0, brdf_error_mean = 0;
  double fit_time_mean_s = 0;
  std::string worst_sphere_material;
  double worst_sphere_db = 0;
  double worst_held_out_min_db = 0;
  double worst_albedo_error = 0;
  std::string Report() const;  // one line
};
MaterialStudySummary Summarize(const std::vector<MaterialStudyRow>& rows);

// The per-material markdown table (one row per material, then mean and worst rows).
std::string MarkdownTable(const std::vector<MaterialStudyRow>& rows, const StudyPlan& plan);

// The rung side-by-side table: one row per material and rung (chosen: validation's choice;
// best: highest sphere mean), then the summary per rung, for the validation-chosen rung and for
// the best rung (mean and worst material of each figure). `albedo_goal`: the relative albedo
// error the summary counts materials within (e.g. 0.05).
std::string LadderMarkdown(const std::vector<MaterialStudyRow>& rows, const StudyPlan& plan,
                           double albedo_goal);

// The export's loss per material: the written (chosen) rung's sphere mean against the truth
// beside its glTF version's, the difference, and the glTF version against the rung; then the
// means over materials.
std::string GltfMarkdown(const std::vector<MaterialStudyRow>& rows);

// One rung's (or the chosen / best rung's) figures summarised over materials.
struct RungSummary {
  std::string name;
  int materials = 0;  // judged (rung fitted)
  double sphere_mean_db = 0, worst_sphere_db = 0;
  std::string worst_sphere_material;
  double held_out_mean_db = 0, worst_held_out_min_db = 0;
  int held_out_materials = 0;  // those with a defined held-out mean (not brdf_only, not all black)
  double albedo_error_mean = 0, worst_albedo_error = 0;
  std::string worst_albedo_material;
  int albedo_within_goal = 0;
  double brdf_error_mean = 0, size_bytes_mean = 0, fit_s_mean = 0;
};
// kind: a rung name, "chosen" or "best".
RungSummary SummarizeRung(const std::vector<MaterialStudyRow>& rows, const std::string& kind,
                          double albedo_goal);

// SVG plot: sphere mean PSNR of every rung per material (one series per rung).
std::string LadderPlot(const std::vector<MaterialStudyRow>& rows, const std::string& title);

// SVG plot: sphere PSNR (mean and worst light) and held-out normalized sample PSNR per material.
std::string StudyPlot(const std::vector<MaterialStudyRow>& rows, const std::string& title);

}  // namespace brdfrig::jobs
