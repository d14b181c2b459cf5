#include "jobs/material_study.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "brdf/nbrdf_library.h"
#include "common/angles.h"
#include "common/error.h"
#include "common/format.h"
#include "coverage/designer.h"
#include "evaluate/sample_figures.h"
#include "evaluate/svg_plot.h"
#include "prior/measured_prior.h"
#include "sim/scene.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;

double Mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0 : sum / static_cast<double>(v.size());
}

// The headline figures of one judged fit. The held-out figures are over the views whose
// normalized figure is defined (the truth not black over the sample; `held_views` of them).
void Headline(const evaluate::MaterialFigures& f, double* sphere_mean, double* sphere_worst,
              double* held_mean, double* held_min, int* held_views, double* albedo) {
  *sphere_mean = f.sphere.mean_psnr_db;
  *sphere_worst = f.sphere.worst_psnr_db;
  std::vector<double> views;
  for (const evaluate::HeldOutResult& v : f.held_out) {
    views.push_back(v.normalized_sample.psnr_db);
  }
  const evaluate::DefinedMean held = evaluate::MeanOfDefined(views);
  *held_mean = held.mean;
  *held_views = held.count;
  *held_min = NAN;
  for (const double v : views) {
    if (!std::isnan(v) && (std::isnan(*held_min) || v < *held_min)) *held_min = v;
  }
  *albedo = 0;
  for (const evaluate::AlbedoAtAngle& a : f.brdf.albedo) {
    if (a.theta_in_deg <= 75) *albedo = std::max(*albedo, a.relative_error);
  }
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

StudyPlan DesignedPlan(int count, const fs::path& scene) {
  const fs::path base =
      scene.empty() ? fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml" : scene;
  const sim::Scene loaded = sim::LoadScene(base);
  coverage::DesignOptions options;
  options.count = count;
  const coverage::PlanDesign design = coverage::DesignPlan(loaded.rig, options);
  StudyPlan plan{"designed (" + std::to_string(count) + " positions, coverage::DesignPlan, " +
                     Fixed(100 * design.covered_fraction, 1) + " % of (θh, θd) cells)",
                 design.Positions()};
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
  if (!model.empty()) (void)brdf::ParseModelKind(model);  // throws for an unknown kind
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
  if (std::isfinite(gltf_sphere_mean_db)) {
    out << "; glTF version sphere " << Fixed(gltf_sphere_mean_db, 2) << " dB (worst light "
        << Fixed(gltf_sphere_worst_db, 2) << "), " << Fixed(gltf_vs_rung_db, 2)
        << " dB against the rung";
  }
  for (std::size_t i = 0; i < rungs.size(); ++i) {
    const RungRow& r = rungs[i];
    out << "\n    " << r.kind << (r.chosen ? " [chosen]" : "")
        << (static_cast<int>(i) == best ? " [best]" : "") << ": ";
    if (!r.fitted) {
      out << "not fitted: " << r.error;
      continue;
    }
    out << "sphere " << Fixed(r.sphere_mean_db, 2) << " dB (worst " << Fixed(r.sphere_worst_db, 2)
        << "), held-out " << Fixed(r.held_out_mean_db, 2) << " (min " << Fixed(r.held_out_min_db, 2)
        << (r.held_out_worst_view.empty() ? "" : " " + r.held_out_worst_view) << "), albedo err "
        << Fixed(r.albedo_error_0_75, 3) << ", BRDF err " << Fixed(r.brdf_error, 3) << ", "
        << r.size_bytes << " B, fit " << Fixed(r.fit_s, 2) << " s";
  }
  return out.str();
}

const prior::MeasuredPrior* LeaveOneOutPriors::For(const StudyMaterial& material) {
  const prior::PriorBuildOptions build = prior::OptionsOf(prior::DefaultPrior());
  // One lock for reading the training set and building: builds are seconds against minutes
  // of capture and judging, and a std::map's elements stay where they are as it grows.
  const std::lock_guard lock(mutex_);
  if (!training_) training_ = prior::ReadTrainingSet({brdf::NbrdfDirectory()}, build);
  for (std::size_t i = 0; i < training_->materials.size(); ++i) {
    if (material.brdf_yaml != "{model: nbrdf, name: " + training_->materials[i].name + "}") {
      continue;
    }
    auto [it, added] = built_.try_emplace(material.name);
    if (added) it->second = prior::BuildPrior(*training_, build, static_cast<int>(i));
    return &it->second;
  }
  return nullptr;
}

std::string FileStem(const std::string& name) {
  std::string stem = name;
  for (char& c : stem) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  }
  return stem;
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
  s.model = options.model;
  s.judge_every_rung = options.every_rung;
  s.judge_brdf_only = options.brdf_only;
  if (options.prior_for) s.prior = options.prior_for(material);
  s.depart = options.depart;
  s.believed_rig = options.believed_rig;
  s.calibration = options.calibration;
  if (!options.keep_materials_dir.empty()) {
    fs::create_directories(options.keep_materials_dir);
    s.keep_material = options.keep_materials_dir / (FileStem(material.name) + ".json");
  }
  const auto start = std::chrono::steady_clock::now();
  try {
    row.result = RunStudyPoint(s);
  } catch (const std::exception& e) {
    row.error = e.what();
    return row;
  }
  row.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Headline(row.result.figures, &row.sphere_mean_db, &row.sphere_worst_db, &row.held_out_mean_db,
           &row.held_out_min_db, &row.held_out_views, &row.albedo_error_0_75);
  if (row.result.gltf_sphere) {
    row.gltf_sphere_mean_db = row.result.gltf_sphere->mean_psnr_db;
    row.gltf_sphere_worst_db = row.result.gltf_sphere->worst_psnr_db;
    // A number, or text ("inf") where the figure is not finite.
    const nlohmann::json figure = row.result.material.gltf_fit.value(
        "/sphere_vs_model/mean_psnr_db"_json_pointer, nlohmann::json());
    row.gltf_vs_rung_db = figure.is_number() ? figure.get<double>() : NAN;
  }
  for (const RungFigures& r : row.result.rungs) {
    RungRow rung;
    rung.kind = r.kind;
    rung.fitted = r.fitted;
    rung.error = r.error;
    rung.chosen = r.chosen;
    rung.validation_score = r.validation_score;
    rung.fit_s = r.fit_seconds;
    rung.size_bytes = r.size_bytes;
    if (r.fitted) {
      int views = 0;
      Headline(r.figures, &rung.sphere_mean_db, &rung.sphere_worst_db, &rung.held_out_mean_db,
               &rung.held_out_min_db, &views, &rung.albedo_error_0_75);
      rung.brdf_error = r.brdf_error;
      for (const evaluate::HeldOutResult& v : r.figures.held_out) {
        if (v.normalized_sample.psnr_db == rung.held_out_min_db) {
          rung.held_out_worst_view = v.view.name;
        }
      }
      for (const evaluate::SphereLight& l : r.figures.sphere.lights) {
        if (l.psnr_db == rung.sphere_worst_db) rung.sphere_worst_light_deg = l.light_angle_deg;
      }
    }
    const int index = static_cast<int>(row.rungs.size());
    if (rung.chosen) row.chosen = index;
    if (rung.fitted && (row.best < 0 || rung.sphere_mean_db > row.rungs[row.best].sphere_mean_db)) {
      row.best = index;
    }
    row.rungs.push_back(std::move(rung));
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

std::string GltfMarkdown(const std::vector<MaterialStudyRow>& rows) {
  std::ostringstream out;
  out << "| material | chosen rung | rung vs truth (dB) | glTF version vs truth (dB) | loss (dB) | "
         "glTF version vs rung (dB) |\n|---|---|---|---|---|---|\n";
  std::vector<double> rung, gltf, loss, vs_rung;
  int worse = 0;
  for (const MaterialStudyRow& r : rows) {
    out << "| " << r.material.name << " |";
    if (!r.error.empty()) {
      out << " failed: " << r.error << " | | | | |\n";
      continue;
    }
    out << " " << brdf::ModelKindName(r.result.material.kind) << " | " << Fixed(r.sphere_mean_db, 1)
        << " |";
    if (!std::isfinite(r.gltf_sphere_mean_db)) {
      out << " no glTF version | | |\n";
      continue;
    }
    const double d = r.sphere_mean_db - r.gltf_sphere_mean_db;
    out << " " << Fixed(r.gltf_sphere_mean_db, 1) << " | " << Fixed(d, 1) << " | "
        << Fixed(r.gltf_vs_rung_db, 1) << " |\n";
    rung.push_back(r.sphere_mean_db);
    gltf.push_back(r.gltf_sphere_mean_db);
    loss.push_back(d);
    if (std::isfinite(r.gltf_vs_rung_db)) vs_rung.push_back(r.gltf_vs_rung_db);
    worse += d > 0;
  }
  out << "| **mean over " << rung.size() << "** | | " << Fixed(Mean(rung), 1) << " | "
      << Fixed(Mean(gltf), 1) << " | " << Fixed(Mean(loss), 1) << " | " << Fixed(Mean(vs_rung), 1)
      << " |\n\nThe glTF version is below the chosen rung on " << worse << " of " << rung.size()
      << " materials.\n";
  return out.str();
}

RungSummary SummarizeRung(const std::vector<MaterialStudyRow>& rows, const std::string& kind,
                          double albedo_goal) {
  RungSummary s;
  s.name = kind;
  std::vector<double> sphere, held, albedo, brdf_error, size, fit;
  s.worst_sphere_db = std::numeric_limits<double>::infinity();
  s.worst_held_out_min_db = std::numeric_limits<double>::infinity();
  for (const MaterialStudyRow& row : rows) {
    if (!row.error.empty()) continue;
    const RungRow* r = nullptr;
    if (kind == "chosen") {
      if (row.chosen >= 0) r = &row.rungs[row.chosen];
    } else if (kind == "best") {
      if (row.best >= 0) r = &row.rungs[row.best];
    } else {
      for (const RungRow& x : row.rungs) {
        if (x.kind == kind) r = &x;
      }
    }
    if (r == nullptr || !r->fitted) continue;
    ++s.materials;
    sphere.push_back(r->sphere_mean_db);
    held.push_back(r->held_out_mean_db);
    albedo.push_back(r->albedo_error_0_75);
    brdf_error.push_back(r->brdf_error);
    size.push_back(static_cast<double>(r->size_bytes));
    fit.push_back(r->fit_s);
    if (r->sphere_mean_db < s.worst_sphere_db) {
      s.worst_sphere_db = r->sphere_mean_db;
      s.worst_sphere_material = row.material.name;
    }
    if (std::isfinite(r->held_out_min_db))
      s.worst_held_out_min_db = std::min(s.worst_held_out_min_db, r->held_out_min_db);
    if (r->albedo_error_0_75 >= s.worst_albedo_error) {
      s.worst_albedo_error = r->albedo_error_0_75;
      s.worst_albedo_material = row.material.name;
    }
    if (r->albedo_error_0_75 <= albedo_goal) ++s.albedo_within_goal;
  }
  s.sphere_mean_db = Mean(sphere);
  // A material without a defined held-out mean is left out of it, and the table says so.
  const evaluate::DefinedMean held_out = evaluate::MeanOfDefined(held);
  s.held_out_mean_db = held_out.mean;
  s.held_out_materials = held_out.count;
  if (held_out.count == 0) s.worst_held_out_min_db = NAN;
  s.albedo_error_mean = Mean(albedo);
  s.brdf_error_mean = Mean(brdf_error);
  s.size_bytes_mean = Mean(size);
  s.fit_s_mean = Mean(fit);
  return s;
}

std::string LadderMarkdown(const std::vector<MaterialStudyRow>& rows, const StudyPlan& plan,
                           double albedo_goal) {
  std::ostringstream out;
  out << "Plan: " << plan.name << " (" << plan.positions.size() << " positions).\n\n";
  out << "| material | rung | sphere mean (dB) | sphere worst light (dB @ light) | held-out mean "
         "(dB) | held-out min (dB) | albedo err 0–75° | BRDF err | size (B) | fit (s) | "
         "validation score |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<std::string> kinds;
  for (const MaterialStudyRow& row : rows) {
    if (!row.error.empty()) {
      out << "| " << row.material.name << " | failed: " << row.error << " | | | | | | | | | |\n";
      continue;
    }
    for (std::size_t i = 0; i < row.rungs.size(); ++i) {
      const RungRow& r = row.rungs[i];
      if (std::find(kinds.begin(), kinds.end(), r.kind) == kinds.end()) kinds.push_back(r.kind);
      std::string mark;
      if (r.chosen) mark += " (chosen)";
      if (static_cast<int>(i) == row.best) mark += " **(best)**";
      out << "| " << (i == 0 ? row.material.name : "") << " | " << r.kind << mark << " |";
      if (!r.fitted) {
        out << " not fitted: " << r.error << " | | | | | | | | |\n";
        continue;
      }
      out << " " << Fixed(r.sphere_mean_db, 1) << " | " << Fixed(r.sphere_worst_db, 1) << " @ "
          << Fixed(r.sphere_worst_light_deg, 0) << "° | " << Fixed(r.held_out_mean_db, 1) << " | "
          << Fixed(r.held_out_min_db, 1)
          << (r.held_out_worst_view.empty() ? "" : " @ " + r.held_out_worst_view) << " | "
          << Fixed(r.albedo_error_0_75, 3) << " | " << Fixed(r.brdf_error, 3) << " | "
          << r.size_bytes << " | " << Fixed(r.fit_s, 2) << " | " << Fixed(r.validation_score, 4)
          << " |\n";
    }
  }
  std::string black_views;
  for (const MaterialStudyRow& row : rows) {
    const int total = static_cast<int>(row.result.figures.held_out.size());
    if (row.error.empty() && row.held_out_views < total) {
      black_views += (black_views.empty() ? "" : ", ") + row.material.name + " " +
                     std::to_string(total - row.held_out_views) + " of " + std::to_string(total);
    }
  }
  if (!black_views.empty()) {
    out << "\nHeld-out views left out of the held-out figures because the truth is black over the "
           "sample there (nothing to normalize by; evaluate/sample_figures.h): "
        << black_views << ".\n";
  }
  out << "\nSummary over materials (mean; worst material beside it). Albedo goal: relative "
         "error ≤ "
      << Fixed(albedo_goal, 2) << ".\n\n";
  out << "| rung | materials | sphere mean (dB) | worst sphere (dB, material) | held-out mean (dB) "
         "| held-out min over views (dB) | albedo err mean | worst albedo err (material) | "
         "albedo within goal | BRDF err mean | size mean (B) | fit mean (s) |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  kinds.push_back("chosen");
  kinds.push_back("best");
  for (const std::string& kind : kinds) {
    const RungSummary s = SummarizeRung(rows, kind, albedo_goal);
    const std::string name = kind == "chosen" ? "**validation-chosen**"
                             : kind == "best" ? "**best by sphere**"
                                              : kind;
    out << "| " << name << " | " << s.materials << " | " << Fixed(s.sphere_mean_db, 1) << " | "
        << Fixed(s.worst_sphere_db, 1) << " (" << s.worst_sphere_material << ") | "
        << Fixed(s.held_out_mean_db, 1)
        << (s.held_out_materials > 0 && s.held_out_materials < s.materials
                ? " (over " + std::to_string(s.held_out_materials) + ")"
                : "")
        << " | " << Fixed(s.worst_held_out_min_db, 1) << " | " << Fixed(s.albedo_error_mean, 3)
        << " | " << Fixed(s.worst_albedo_error, 3) << " (" << s.worst_albedo_material << ") | "
        << s.albedo_within_goal << "/" << s.materials << " | " << Fixed(s.brdf_error_mean, 3)
        << " | " << Fixed(s.size_bytes_mean, 0) << " | " << Fixed(s.fit_s_mean, 2) << " |\n";
  }
  // Which rung validation chose and which was best, counted.
  std::map<std::string, int> chosen, best;
  int agree = 0, judged = 0;
  for (const MaterialStudyRow& row : rows) {
    if (!row.error.empty() || row.chosen < 0 || row.best < 0) continue;
    ++judged;
    ++chosen[row.rungs[row.chosen].kind];
    ++best[row.rungs[row.best].kind];
    agree += row.chosen == row.best;
  }
  out << "\nValidation chose:";
  for (const auto& [k, n] : chosen) out << " " << k << " " << n << ";";
  out << " best by sphere:";
  for (const auto& [k, n] : best) out << " " << k << " " << n << ";";
  out << " the same rung on " << agree << " of " << judged << " materials.\n";
  return out.str();
}

std::string LadderPlot(const std::vector<MaterialStudyRow>& rows, const std::string& title) {
  std::vector<evaluate::Series> series;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (const RungRow& r : rows[i].rungs) {
      if (!r.fitted) continue;
      auto it = std::find_if(series.begin(), series.end(),
                             [&](const evaluate::Series& x) { return x.label == r.kind; });
      if (it == series.end()) {
        series.push_back({r.kind, {}, {}, false});
        it = series.end() - 1;
      }
      it->x.push_back(static_cast<double>(i + 1));
      it->y.push_back(r.sphere_mean_db);
    }
  }
  return evaluate::SvgLinePlot(
      series, {title, "material (row of the table)", "sphere mean PSNR (dB)", 720, 420});
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
