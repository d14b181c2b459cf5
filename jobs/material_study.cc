#include "jobs/material_study.h"
#include "common/angles.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/format.h"
#include "evaluate/svg_plot.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

double Mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0 : sum / static_cast<double>(v.size());
}

}  // namespace

std::vector<StudyMaterial> AnalyticStudyMaterials() {
  const std::string metal = "f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]";
  const std::string plastic = "f0: 0.04, diffuse: [0.5, 0.15, 0.1]";
  return {
      {"GGX alpha 0.05 (metal)", "{model: ggx, alpha: 0.05, " + metal + "}"},
      {"GGX alpha 0.1 (metal)", "{model: ggx, alpha: 0.1, " + metal + "}"},
      {"GGX alpha 0.3 (plastic)", "{model: ggx, alpha: 0.3, " + plastic + "}"},
      {"Beckmann/Cook-Torrance m 0.1",
       "{model: cook_torrance, alpha: 0.1, f0: 0.5, "
       "diffuse: [0.2, 0.1, 0.05]}"},
      {"Beckmann/Cook-Torrance m 0.3", "{model: cook_torrance, alpha: 0.3, " + plastic + "}"},
      {"Ward alpha 0.1", "{model: ward, alpha: 0.1, specular: 0.3, diffuse: [0.15, 0.2, 0.3]}"},
      {"Ward alpha 0.25", "{model: ward, alpha: 0.25, specular: 0.2, diffuse: [0.3, 0.3, 0.1]}"},
      {"Lambert + Blinn-Phong n=50",
       "{model: blinn_phong, exponent: 50, specular: 0.3, "
       "diffuse: [0.4, 0.3, 0.2]}"},
      {"Lambert + Blinn-Phong n=500",
       "{model: blinn_phong, exponent: 500, specular: 0.5, "
       "diffuse: [0.2, 0.3, 0.4]}"},
  };
}

std::vector<StudyMaterial> MeasuredStudyMaterials(const fs::path& dir) {
  std::vector<StudyMaterial> out;
  if (!fs::is_directory(dir)) return out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    out.push_back({name, "{model: nbrdf, name: " + name + "}"});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return out;
}

StudyPlan MirrorPlan() {
  StudyPlan plan{"mirror (symmetric arms 15..65 deg)", {}};
  for (double theta = 15; theta <= 65; theta += 10) {
    plan.positions.push_back({{"camera_arm", Radians(theta)}, {"light_arm", -Radians(theta)}});
  }
  return plan;
}

void MaterialStudyOptions::Validate() const {
  if (width < 64 || height < 48) {
    throw OptionsError("material study: resolution " + std::to_string(width) + "x" +
                       std::to_string(height) + " must be at least 64x48 px");
  }
  if (supersampling < 1) {
    throw OptionsError("material study: supersampling = " + std::to_string(supersampling) +
                       " must be >= 1");
  }
  if (work_dir.empty()) throw OptionsError("material study: work_dir is empty");
  judge.Validate();
}

std::string MaterialStudyRow::Report() const {
  if (!error.empty()) return material.name + ": failed: " + error;
  std::ostringstream out;
  out << material.name << ": sphere " << Fixed(sphere_mean_db, 2) << " dB (worst light "
      << Fixed(sphere_worst_db, 2) << "), held-out normalized " << Fixed(held_out_mean_db, 2)
      << " dB (min " << Fixed(held_out_min_db, 2) << "), albedo error "
      << Fixed(albedo_error_0_75, 3) << ", BRDF err " << Fixed(result.brdf_error, 3) << ", fit "
      << Fixed(result.reconstruct_time_s, 2) << " s";
  return out.str();
}

MaterialStudyRow RunMaterialStudyPoint(const StudyMaterial& material, const StudyPlan& plan,
                                       const MaterialStudyOptions& options) {
  options.Validate();
  MaterialStudyRow row;
  row.material = material;
  StudySettings s;
  s.scene = options.scene;
  s.positions = plan.positions;
  s.width = options.width;
  s.height = options.height;
  s.supersampling = options.supersampling;
  s.sample_brdf = material.brdf_yaml;
  s.work_dir = options.work_dir;
  s.judge = options.judge;
  const auto start = std::chrono::steady_clock::now();
  try {
    row.result = RunStudyPoint(s);
  } catch (const std::exception& e) {
    row.error = e.what();
    return row;
  }
  row.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const evaluate::MaterialFigures& f = row.result.figures;
  row.sphere_mean_db = f.sphere.mean_psnr_db;
  row.sphere_worst_db = f.sphere.worst_psnr_db;
  row.held_out_min_db = std::numeric_limits<double>::infinity();
  for (const evaluate::HeldOutResult& v : f.held_out) {
    row.held_out_mean_db += v.normalized_sample.psnr_db / static_cast<double>(f.held_out.size());
    row.held_out_min_db = std::min(row.held_out_min_db, v.normalized_sample.psnr_db);
  }
  for (const evaluate::AlbedoAtAngle& a : f.brdf.albedo) {
    if (a.theta_in_deg <= 75)
      row.albedo_error_0_75 = std::max(row.albedo_error_0_75, a.relative_error);
  }
  return row;
}

std::string MaterialStudySummary::Report() const {
  std::ostringstream out;
  out << materials << " materials (" << failed << " failed): sphere mean "
      << Fixed(sphere_mean_db, 2) << " dB, worst " << worst_sphere_material << " "
      << Fixed(worst_sphere_db, 2) << " dB; held-out normalized mean " << Fixed(held_out_mean_db, 2)
      << " dB, worst view " << Fixed(worst_held_out_min_db, 2) << " dB; albedo error mean "
      << Fixed(albedo_error_mean, 3) << ", worst " << Fixed(worst_albedo_error, 3)
      << "; BRDF err mean " << Fixed(brdf_error_mean, 3) << "; fit " << Fixed(fit_time_mean_s, 2)
      << " s mean";
  return out.str();
}

MaterialStudySummary Summarize(const std::vector<MaterialStudyRow>& rows) {
  MaterialStudySummary s;
  std::vector<double> sphere, held, albedo, brdf_error, fit;
  s.worst_sphere_db = std::numeric_limits<double>::infinity();
  s.worst_held_out_min_db = std::numeric_limits<double>::infinity();
  for (const MaterialStudyRow& r : rows) {
    ++s.materials;
    if (!r.error.empty()) {
      ++s.failed;
      continue;
    }
    sphere.push_back(r.sphere_mean_db);
    held.push_back(r.held_out_mean_db);
    albedo.push_back(r.albedo_error_0_75);
    brdf_error.push_back(r.result.brdf_error);
    fit.push_back(r.result.reconstruct_time_s);
    if (r.sphere_mean_db < s.worst_sphere_db) {
      s.worst_sphere_db = r.sphere_mean_db;
      s.worst_sphere_material = r.material.name;
    }
    s.worst_held_out_min_db = std::min(s.worst_held_out_min_db, r.held_out_min_db);
    s.worst_albedo_error = std::max(s.worst_albedo_error, r.albedo_error_0_75);
  }
  s.sphere_mean_db = Mean(sphere);
  s.held_out_mean_db = Mean(held);
  s.albedo_error_mean = Mean(albedo);
  s.brdf_error_mean = Mean(brdf_error);
  s.fit_time_mean_s = Mean(fit);
  return s;
}

std::string MarkdownTable(const std::vector<MaterialStudyRow>& rows, const StudyPlan& plan) {
  // Columns follow the first successful row's lights and elevations.
  const MaterialStudyRow* first = nullptr;
  for (const auto& r : rows) {
    if (r.error.empty()) {
      first = &r;
      break;
    }
  }
  std::ostringstream out;
  out << "Plan: " << plan.name << " (" << plan.positions.size() << " positions).\n\n";
  out << "| material | sphere mean (dB) |";
  std::vector<double> elevations;
  if (first) {
    for (const evaluate::SphereLight& l : first->result.figures.sphere.lights) {
      out << " sphere " << Fixed(l.light_angle_deg, 0) << "° |";
    }
    for (const evaluate::ElevationSummary& e :
         evaluate::SummarizeByElevation(first->result.figures.held_out)) {
      out << " held-out el " << Fixed(e.elevation_deg, 0) << "° (dB) |";
      elevations.push_back(e.elevation_deg);
    }
  }
  out << " held-out min (dB) | rel. RMSE | albedo err 0–75° | albedo err 80° | BRDF err | slices | "
         "fit (s) |\n|---|---|";
  const std::size_t extra =
      first ? first->result.figures.sphere.lights.size() + elevations.size() : 0;
  for (std::size_t i = 0; i < extra + 7; ++i) out << "---|";
  out << "\n";
  for (const MaterialStudyRow& r : rows) {
    out << "| " << r.material.name << " |";
    if (!r.error.empty()) {
      out << " failed: " << r.error << " |\n";
      continue;
    }
    const evaluate::MaterialFigures& f = r.result.figures;
    out << " " << Fixed(r.sphere_mean_db, 1) << " |";
    for (const evaluate::SphereLight& l : f.sphere.lights)
      out << " " << Fixed(l.psnr_db, 1) << " |";
    double rmse = 0;
    for (const evaluate::ElevationSummary& e : evaluate::SummarizeByElevation(f.held_out)) {
      out << " " << Fixed(e.normalized_sample_psnr_db, 1) << " |";
      rmse += e.relative_rmse / static_cast<double>(elevations.size());
    }
    const double albedo_80 = f.brdf.albedo.empty() ? NAN : f.brdf.albedo.back().relative_error;
    out << " " << Fixed(r.held_out_min_db, 1) << " | " << Fixed(rmse, 3) << " | "
        << Fixed(r.albedo_error_0_75, 3) << " | " << Fixed(albedo_80, 3) << " | "
        << Fixed(r.result.brdf_error, 3) << " | " << r.result.slices << " | "
        << Fixed(r.result.reconstruct_time_s, 2) << " |\n";
  }
  const MaterialStudySummary s = Summarize(rows);
  out << "\nMean over " << s.materials - s.failed << " materials: sphere "
      << Fixed(s.sphere_mean_db, 1) << " dB, held-out normalized sample "
      << Fixed(s.held_out_mean_db, 1) << " dB, albedo error (0–75°) "
      << Fixed(s.albedo_error_mean, 3) << ", BRDF err " << Fixed(s.brdf_error_mean, 3) << ", fit "
      << Fixed(s.fit_time_mean_s, 2) << " s. Worst: sphere " << Fixed(s.worst_sphere_db, 1)
      << " dB (" << s.worst_sphere_material << "), held-out view "
      << Fixed(s.worst_held_out_min_db, 1) << " dB, albedo error " << Fixed(s.worst_albedo_error, 3)
      << ". Failed: " << s.failed << ".\n";
  return out.str();
}

std::string StudyPlot(const std::vector<MaterialStudyRow>& rows, const std::string& title) {
  evaluate::Series mean{"sphere mean", {}, {}, false}, worst{"sphere worst light", {}, {}, false},
      held{"held-out normalized sample mean", {}, {}, false};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].error.empty()) continue;
    const double x = static_cast<double>(i + 1);
    mean.x.push_back(x);
    mean.y.push_back(rows[i].sphere_mean_db);
    worst.x.push_back(x);
    worst.y.push_back(rows[i].sphere_worst_db);
    held.x.push_back(x);
    held.y.push_back(rows[i].held_out_mean_db);
  }
  return evaluate::SvgLinePlot({mean, worst, held},
                               {title, "material (row of the table)", "PSNR (dB)", 720, 420});
}

}  // namespace brdfrig::jobs
