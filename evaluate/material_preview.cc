#include "evaluate/material_preview.h"

#include <cmath>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "brdf/gltf_model.h"
#include "common/error.h"
#include "common/format.h"
#include "evaluate/material_report.h"

namespace brdfrig::evaluate {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Db(const json& value) { return Fixed(NumberFromJson(value), 2) + " dB"; }

// One row of spheres: images (written under report_dir/preview/) and, against a reference, the
// PSNR per light.
json Row(const std::string& role, const std::string& label, const SphereTestResult& result,
         bool reference_images, const std::string& against, const fs::path& report_dir) {
  json row = {{"role", role}, {"label", label}};
  if (!against.empty()) {
    row["against"] = against;
    row["psnr_db"] = json::array();
    for (const SphereLight& l : result.lights) row["psnr_db"].push_back(JsonNumber(l.psnr_db));
    row["mean_psnr_db"] = JsonNumber(result.mean_psnr_db);
  }
  if (!report_dir.empty()) {
    fs::create_directories(report_dir / "preview");
    row["images"] = json::array();
    for (const SphereLight& l : result.lights) {
      const std::string file =
          "preview/" + role + "_light" + std::to_string(std::lround(l.light_angle_deg)) + ".png";
      const cv::Mat& image = reference_images ? l.truth_image : l.fitted_image;
      if (!cv::imwrite((report_dir / file).string(), image)) {
        throw OutputError("cannot write " + (report_dir / file).string());
      }
      row["images"].push_back(file);
    }
  }
  return row;
}

}  // namespace

std::shared_ptr<const brdf::Brdf> GltfVersionOf(const brdf::Material& material,
                                                std::string* why_not) {
  std::string reason;
  if (material.kind == brdf::ModelKind::kGltf) {
    reason = "the material is itself of the gltf kind: the fit's row is its glTF version";
  } else if (!material.gltf) {
    reason =
        "no glTF version: material.json has no gltf block (written by reconstructions since "
        "the gltf kind; `brdfrig export` fits one for older files)";
  } else {
    return std::make_shared<brdf::GltfModel>(*material.gltf);
  }
  if (why_not) *why_not = reason;
  return nullptr;
}

json MaterialPreviewJson(const PreviewModels& models, const SphereTestOptions& sphere_options,
                         const fs::path& report_dir) {
  if (models.fit == nullptr) throw Error("material preview: no fitted material");
  SphereTestOptions sphere = sphere_options;
  sphere.keep_images = true;
  // Without a truth the fit is the reference: its own scale for the images, and the glTF
  // version's PSNR measures what the conversion lost.
  const brdf::Brdf& reference = models.truth ? *models.truth : *models.fit;
  const std::string against = models.truth ? "truth" : "";
  const SphereTestResult fit = SphereTest(reference, *models.fit, sphere);
  json out = {{"protocol", fit.protocol},
              {"reference", models.truth ? "truth" : "none"},
              {"light_angles_deg", sphere.light_angles_deg},
              {"rows", json::array()}};
  if (models.truth) {
    out["rows"].push_back(Row("truth", "truth (the scene's BRDF)", fit, true, "", report_dir));
  }
  out["rows"].push_back(Row("fit", models.fit_label.empty() ? "fit" : models.fit_label, fit, false,
                            against, report_dir));
  if (models.gltf) {
    const SphereTestResult gltf = SphereTest(reference, *models.gltf, sphere);
    out["rows"].push_back(
        Row("gltf", "glTF version", gltf, false, models.truth ? "truth" : "fit", report_dir));
  } else {
    out["gltf_note"] = models.gltf_note.empty() ? "no glTF version" : models.gltf_note;
  }
  if (!models.gltf_file.empty()) out["gltf_file"] = models.gltf_file;
  return out;
}

ReportSection MaterialPreviewSection(const json& p, const json* validation_photos,
                                     const json* validation_photos_gltf) {
  ReportSection s{"The material", {}, {}, {}, {}};
  const bool truth = p.at("reference").get<std::string>() == "truth";
  s.paragraphs.push_back(
      std::string(truth ? "The fitted material beside the truth"
                        : "The fitted material (a hardware capture has no truth: beside it the "
                          "validation photos)") +
      " on a sphere under a directional light at several angles from the view direction, "
      "the sphere test's protocol: " +
      p.at("protocol").get<std::string>() +
      (truth ? "."
             : " (without a truth the fit is the reference: its own scale, and the glTF "
               "version's PSNR is against it)."));
  if (p.contains("gltf_note")) s.paragraphs.push_back(p.at("gltf_note").get<std::string>() + ".");
  if (p.contains("gltf_file")) {
    s.paragraphs.push_back("glTF 2.0 export: " + p.at("gltf_file").get<std::string>() + ".");
  }
  ImageGrid spheres{"The material on a sphere; PSNR against the " +
                        std::string(truth ? "truth" : "fit") + " under each image",
                    {},
                    {}};
  for (const json& a : p.at("light_angles_deg")) {
    spheres.columns.push_back("light " + Fixed(a.get<double>(), 0) + "°");
  }
  for (const json& row : p.at("rows")) {
    ImageGridRow r;
    r.label = row.at("label").get<std::string>();
    if (row.contains("mean_psnr_db")) {
      r.label += " (mean " + Db(row.at("mean_psnr_db")) + " against the " +
                 row.at("against").get<std::string>() + ")";
    }
    for (std::size_t i = 0; i < spheres.columns.size(); ++i) {
      ImageCell cell;
      if (row.contains("images")) cell.file = row.at("images").at(i).get<std::string>();
      if (row.contains("psnr_db")) cell.caption = Db(row.at("psnr_db").at(i));
      r.cells.push_back(cell);
    }
    spheres.rows.push_back(r);
  }
  s.grids.push_back(spheres);
  if (validation_photos != nullptr) {
    ImageGrid photos{
        "Validation photos (not fitted) beside the fit's prediction under the "
        "geometry measured from each photo; normalized sample PSNR",
        {},
        {}};
    ImageGridRow photo_row{"photo (HDR)", {}}, fit_row{"fit's prediction", {}},
        gltf_row{"glTF version's prediction", {}};
    std::map<int, json> gltf_by_position;
    if (validation_photos_gltf != nullptr) {
      for (const json& g : validation_photos_gltf->at("positions")) {
        gltf_by_position[g.at("position").get<int>()] = g;
      }
    }
    for (const json& v : validation_photos->at("positions")) {
      if (!v.at("measured").get<bool>()) continue;
      const int position = v.at("position").get<int>();
      photos.columns.push_back("position " + std::to_string(position) + " (θi " +
                               Fixed(v.at("theta_in_deg").get<double>(), 1) + "°)");
      const json images = v.value("images", json::object());
      photo_row.cells.push_back({images.value("photo", ""), ""});
      fit_row.cells.push_back({images.value("render", ""), Db(v.at("normalized_sample_psnr_db"))});
      const auto g = gltf_by_position.find(position);
      gltf_row.cells.push_back(
          {"", g != gltf_by_position.end() && g->second.at("measured").get<bool>()
                   ? Db(g->second.at("normalized_sample_psnr_db"))
                   : "n/a"});
    }
    if (!photos.columns.empty()) {
      photos.rows = {photo_row, fit_row};
      if (validation_photos_gltf != nullptr) photos.rows.push_back(gltf_row);
      s.grids.push_back(photos);
    }
  }
  return s;
}

}  // namespace brdfrig::evaluate
