// The hemisphere study: for each sample material (analytic or measured), a simulated capture
// on a plan, the reconstruction, and every figure of evaluate/material_report.h. Materials are
// scene `sample.brdf` snippets, so a measured one is `{model: nbrdf, name: <material>}` and
// adding a set is adding lines; plans are explicit position lists, so a designed plan plugs in.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "evaluate/material_report.h"
#include "geometry/rig_geometry.h"
#include "jobs/study.h"

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

struct MaterialStudyOptions {
  std::filesystem::path scene;  // base scene (default: sim/scenes/default.yaml)
  int width = 400, height = 300;
  int supersampling = 1;
  evaluate::JudgeOptions judge;    // the figures (elevations, lights, albedo angles)
  std::filesystem::path work_dir;  // scratch; one subdirectory per material
  void Validate() const;           // throws OptionsError
};

struct MaterialStudyRow {
  StudyMaterial material;
  std::string error;  // non-empty: the point failed (capture, reconstruction or evaluation)
  StudyResult result;
  double wall_s = 0;
  // Headline figures (from result.figures).
  double sphere_mean_db = 0, sphere_worst_db = 0;
  double held_out_mean_db = 0, held_out_min_db = 0;  // normalized sample PSNR over all views
  double albedo_error_0_75 = 0;                      // max relative error, 0°..75°
  std::string Report() const;                        // one line
};

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

// SVG plot: sphere PSNR (mean and worst light) and held-out normalized sample PSNR per material.
std::string StudyPlot(const std::vector<MaterialStudyRow>& rows, const std::string& title);

}  // namespace brdfrig::jobs
