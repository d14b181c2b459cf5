#include "evaluate/material_report.h"

#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "brdf/metrics.h"
#include "common/angles.h"
#include "common/error.h"
#include "common/format.h"
#include "evaluate/display_image.h"
#include "evaluate/sample_figures.h"

namespace brdfrig::evaluate {
namespace {

namespace fs = std::filesystem;

nlohmann::json RgbJson(const brdf::Rgb& c) {
  return nlohmann::json::array({JsonNumber(c[0]), JsonNumber(c[1]), JsonNumber(c[2])});
}

std::string Deg(double radians) { return std::to_string(std::lround(Degrees(radians))); }

}  // namespace

nlohmann::json JsonNumber(double value) {
  if (std::isfinite(value)) return value;
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return "nan";
}

double NumberFromJson(const nlohmann::json& value) {
  if (value.is_number()) return value.get<double>();
  if (value.is_string()) {
    const std::string s = value.get<std::string>();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  }
  throw Error("report.json: expected a number, \"inf\", \"-inf\" or \"nan\", got " + value.dump());
}

std::vector<ElevationSummary> SummarizeByElevation(const std::vector<HeldOutResult>& views) {
  std::map<long, ElevationSummary> by;
  std::map<long, std::vector<double>> normalized;
  for (const HeldOutResult& v : views) {
    const long key = std::lround(Degrees(v.view.elevation) * 1000);
    ElevationSummary& s = by[key];
    s.elevation_deg = Degrees(v.view.elevation);
    ++s.views;
    s.whole_photo_psnr_db += v.whole_photo.psnr_db;
    s.sample_only_psnr_db += v.sample_only.psnr_db;
    normalized[key].push_back(v.normalized_sample.psnr_db);
    s.relative_rmse += v.relative_rmse;
  }
  std::vector<ElevationSummary> out;
  for (auto& [key, s] : by) {
    const double n = s.views;
    s.whole_photo_psnr_db /= n;
    s.sample_only_psnr_db /= n;
    // Views where the truth is black have no normalized figure (evaluate/sample_figures.h).
    const DefinedMean m = MeanOfDefined(normalized[key]);
    s.normalized_sample_psnr_db = m.mean;
    s.normalized_views = m.count;
    s.relative_rmse /= n;
    out.push_back(s);
  }
  return out;
}

void JudgeOptions::Validate() const {
  if (view_phis_deg.empty())
    throw OptionsError("judge: view_phis_deg is empty (no held-out views)");
  if (view_elevations_deg.empty()) throw OptionsError("judge: view_elevations_deg is empty");
  for (double e : view_elevations_deg) {
    if (!(e > 0 && e < 85)) {
      throw OptionsError("judge: view elevation " + Fixed(e, 3) +
                         " deg must be in (0, 85) (the cut-out must stay in view)");
    }
  }
  held_out.Validate();
  sphere.Validate();
  brdf.Validate();
}

std::vector<HeldOutView> JudgeOptions::Views() const {
  std::vector<double> elevations, phis;
  for (double d : view_elevations_deg) elevations.push_back(Radians(d));
  for (double d : view_phis_deg) phis.push_back(Radians(d));
  return ElevationViews(elevations, phis);
}

MaterialFigures JudgeFit(const sim::Scene& scene, const brdf::Brdf& fitted,
                         const JudgeOptions& options) {
  options.Validate();
  MaterialFigures figures = JudgeBrdf(*scene.sample.brdf, fitted, options.sphere, options.brdf);
  figures.held_out = EvaluateHeldOut(scene, fitted, options.Views(), options.held_out);
  return figures;
}

std::vector<MaterialFigures> JudgeFitEach(const sim::Scene& scene,
                                          const std::vector<const brdf::Brdf*>& fitted,
                                          const JudgeOptions& options) {
  options.Validate();
  std::vector<MaterialFigures> figures;
  for (const brdf::Brdf* f : fitted) {
    figures.push_back(JudgeBrdf(*scene.sample.brdf, *f, options.sphere, options.brdf));
  }
  std::vector<std::vector<HeldOutResult>> held =
      EvaluateHeldOutEach(scene, fitted, options.Views(), options.held_out);
  for (std::size_t i = 0; i < fitted.size(); ++i) figures[i].held_out = std::move(held[i]);
  return figures;
}

MaterialFigures JudgeBrdf(const brdf::Brdf& truth, const brdf::Brdf& fitted,
                          const SphereTestOptions& sphere, const BrdfFiguresOptions& brdf) {
  MaterialFigures figures;
  figures.sphere = SphereTest(truth, fitted, sphere);
  figures.brdf = CompareBrdf(truth, fitted, brdf);
  return figures;
}

nlohmann::json FiguresJson(const MaterialFigures& f, const fs::path& report_dir) {
  nlohmann::json out;
  if (!f.held_out.empty()) {
    nlohmann::json held;
    const HeldOutResult& first = f.held_out.front();
    held["protocols"] = {{"whole_photo_psnr_db", first.whole_photo.protocol},
                         {"sample_only_psnr_db", first.sample_only.protocol},
                         {"normalized_sample_psnr_db", first.normalized_sample.protocol},
                         {"relative_rmse", first.relative_rmse_protocol}};
    held["views"] = nlohmann::json::array();
    for (const HeldOutResult& v : f.held_out) {
      nlohmann::json j = {{"name", v.view.name},
                          {"elevation_deg", Degrees(v.view.elevation)},
                          {"phi_deg", Degrees(v.view.phi)},
                          {"whole_photo_psnr_db", JsonNumber(v.whole_photo.psnr_db)},
                          {"sample_only_psnr_db", JsonNumber(v.sample_only.psnr_db)},
                          {"normalized_sample_psnr_db", JsonNumber(v.normalized_sample.psnr_db)},
                          {"relative_rmse", JsonNumber(v.relative_rmse)},
                          {"sample_pixels", v.sample_only.pixels}};
      if (!report_dir.empty() && !v.photo.empty()) {
        fs::create_directories(report_dir / "views");
        const std::string stem = "views/el" + Deg(v.view.elevation) + "_phi" + Deg(v.view.phi);
        const double scale = AutoDisplayScale(v.photo);
        cv::imwrite((report_dir / (stem + "_photo.png")).string(), ToDisplay8(v.photo, scale));
        cv::imwrite((report_dir / (stem + "_render.png")).string(), ToDisplay8(v.rendering, scale));
        cv::imwrite((report_dir / (stem + "_diff.png")).string(),
                    ToDisplay8(DifferenceImage(v.photo, v.rendering), scale));
        j["images"] = {{"photo", stem + "_photo.png"},
                       {"render", stem + "_render.png"},
                       {"diff", stem + "_diff.png"}};
      }
      held["views"].push_back(j);
    }
    held["by_elevation"] = nlohmann::json::array();
    for (const ElevationSummary& s : SummarizeByElevation(f.held_out)) {
      held["by_elevation"].push_back(
          {{"elevation_deg", s.elevation_deg},
           {"views", s.views},
           {"whole_photo_psnr_db", JsonNumber(s.whole_photo_psnr_db)},
           {"sample_only_psnr_db", JsonNumber(s.sample_only_psnr_db)},
           {"normalized_sample_psnr_db", JsonNumber(s.normalized_sample_psnr_db)},
           {"normalized_views", s.normalized_views},
           {"relative_rmse", JsonNumber(s.relative_rmse)}});
    }
    out["held_out"] = held;
  }
  if (!f.sphere.lights.empty()) {
    nlohmann::json sphere = {{"protocol", f.sphere.protocol},
                             {"mean_psnr_db", JsonNumber(f.sphere.mean_psnr_db)},
                             {"worst_psnr_db", JsonNumber(f.sphere.worst_psnr_db)},
                             {"mean_relative_rmse", JsonNumber(f.sphere.mean_relative_rmse)},
                             {"lights", nlohmann::json::array()}};
    for (const SphereLight& l : f.sphere.lights) {
      nlohmann::json j = {{"light_angle_deg", l.light_angle_deg},
                          {"psnr_db", JsonNumber(l.psnr_db)},
                          {"relative_rmse", JsonNumber(l.relative_rmse)},
                          {"scale", JsonNumber(l.scale)},
                          {"pixels", l.pixels}};
      if (!report_dir.empty() && !l.truth_image.empty()) {
        fs::create_directories(report_dir / "spheres");
        const std::string stem = "spheres/light" + std::to_string(std::lround(l.light_angle_deg));
        cv::imwrite((report_dir / (stem + "_truth.png")).string(), l.truth_image);
        cv::imwrite((report_dir / (stem + "_fit.png")).string(), l.fitted_image);
        j["images"] = {{"truth", stem + "_truth.png"}, {"fit", stem + "_fit.png"}};
      }
      sphere["lights"].push_back(j);
    }
    out["sphere"] = sphere;
  }
  if (!f.brdf.albedo.empty()) {
    nlohmann::json b = {{"protocol", f.brdf.protocol},
                        {"log_cosine_error", JsonNumber(f.brdf.log_cosine_error)},
                        {"max_albedo_error", JsonNumber(f.brdf.max_albedo_error)},
                        {"albedo", nlohmann::json::array()}};
    for (const AlbedoAtAngle& a : f.brdf.albedo) {
      b["albedo"].push_back({{"theta_in_deg", a.theta_in_deg},
                             {"truth", RgbJson(a.truth)},
                             {"fitted", RgbJson(a.fitted)},
                             {"relative_error", JsonNumber(a.relative_error)}});
    }
    out["brdf"] = b;
  }
  return out;
}

}  // namespace brdfrig::evaluate
