#include "reconstruct/gltf_export.h"

#include <cmath>

#include "brdf/brdf_file.h"
#include "brdf/gltf_file.h"
#include "brdf/material_file.h"
#include "brdf/nbrdf.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "common/json_parse.h"
#include "common/sha256.h"

namespace brdfrig::reconstruct {
namespace {

// The default rig's cut-out (geometry::TargetGeometry's defaults).
constexpr double kDefaultTileM = 0.1;

// A material file that is not a brdfrig material.json (an nbrdf fit, a MERL table) as a
// material of its own with only the glTF version to give: `kind` is what it is.
bool IsBrdfrigMaterial(const std::filesystem::path& path) {
  if (path.extension() != ".json") return false;
  const nlohmann::json doc = ParseJson(ReadFileToString(path), path.string());
  return !(doc.is_object() && doc.contains("format") && doc["format"] == "nbrdf-mlp");
}

// JSON has no infinity: an identical image's PSNR is written "inf".
nlohmann::json FiniteOrText(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json("inf");
}

double MeanPsnr(const nlohmann::json& fit) {
  const auto it = fit.find("sphere_vs_model");
  if (it == fit.end() || !it->contains("mean_psnr_db")) return std::nan("");
  const nlohmann::json& x = (*it)["mean_psnr_db"];
  return x.is_number() ? x.get<double>() : x == "inf" ? INFINITY : std::nan("");
}

}  // namespace

std::string GltfExportSummary::ToString() const {
  return std::string(fitted_now ? "fitted now" : "as reconstructed") + " from the " + source_kind +
         " material: baseColor " + Fixed(params.base_color[0], 3) + " " +
         Fixed(params.base_color[1], 3) + " " + Fixed(params.base_color[2], 3) + ", metallic " +
         Fixed(params.metallic, 3) + ", roughness " + Fixed(params.roughness, 3) + ", ior " +
         Fixed(params.ior, 3) + ", specular " + Fixed(params.specular, 3) + "; sphere PSNR " +
         Fixed(sphere_vs_model_db, 2) + " dB against the material; tile " +
         Fixed(tile_width_m * 1000, 0) + " × " + Fixed(tile_height_m * 1000, 0) + " mm";
}

GltfExportSummary ExportGltfFile(const std::filesystem::path& material_path,
                                 const std::filesystem::path& output,
                                 const GltfFitOptions& options) {
  const std::string ext = output.extension().string();
  if (ext != ".glb" && ext != ".gltf") {
    throw FileError(output.string(), "a glTF file's name must end in .glb or .gltf");
  }
  GltfExportSummary summary;
  brdf::Material material;
  if (IsBrdfrigMaterial(material_path)) {
    material = brdf::ReadMaterialFile(material_path);
    summary.source_kind = brdf::ModelKindName(material.kind);
  } else {
    // No kind of ours: fitted through the same path, the model being the measured material.
    summary.source_kind = material_path.extension() == ".binary" ? "merl" : "nbrdf";
  }
  if (!material.gltf) {
    summary.fitted_now = true;
    try {
      if (summary.source_kind == "merl" || summary.source_kind == "nbrdf") {
        const std::shared_ptr<const brdf::Brdf> model = brdf::LoadBrdfFile(material_path);
        const GltfFit fit = FitGltf(HemisphereSamples(*model, options), options);
        material.gltf = fit.params;
        const brdf::SphereFigure figure =
            brdf::SpherePsnr(*model, brdf::GltfModel(fit.params), options.sphere);
        material.gltf_fit = {{"source", "the measured material over the whole hemisphere"},
                             {"rung", summary.source_kind},
                             {"residual", fit.residual},
                             {"sphere_vs_model",
                              {{"mean_psnr_db", FiniteOrText(figure.mean_psnr_db)},
                               {"worst_psnr_db", FiniteOrText(figure.worst_psnr_db)}}}};
      } else {
        AddGltfVersion(&material, options);
      }
    } catch (const FileError&) {
      throw;
    } catch (const Error& e) {
      throw FileError(material_path.string(),
                      std::string("its glTF version could not be fitted: ") + e.what());
    }
  }
  summary.params = *material.gltf;
  summary.sphere_vs_model_db = MeanPsnr(material.gltf_fit);

  brdf::GltfScene scene;
  scene.material = *material.gltf;
  scene.name = material_path.stem().string();
  std::string tile_source = "the default rig's cut-out (the material records no cut-out size)";
  scene.tile_width_m = scene.tile_height_m = kDefaultTileM;
  const auto cutout = material.provenance.find("cutout_m");
  if (cutout != material.provenance.end() && cutout->is_array() && cutout->size() == 2 &&
      (*cutout)[0].is_number() && (*cutout)[1].is_number() && (*cutout)[0].get<double>() > 0 &&
      (*cutout)[1].get<double>() > 0) {
    scene.tile_width_m = (*cutout)[0].get<double>();
    scene.tile_height_m = (*cutout)[1].get<double>();
    tile_source = "the capture's cut-out (material.json provenance.cutout_m)";
  }
  summary.tile_width_m = scene.tile_width_m;
  summary.tile_height_m = scene.tile_height_m;
  nlohmann::json provenance = {
      {"source_file", material_path.filename().string()},
      {"source_sha256", Sha256FileHex(material_path)},
      {"source_kind", summary.source_kind},
      {"gltf_version", summary.fitted_now ? "fitted by the export" : "written by reconstruct"},
      {"gltf_fit", material.gltf_fit},
      {"tile_size_m", {scene.tile_width_m, scene.tile_height_m}},
      {"tile_size_source", tile_source}};
  if (material.provenance.contains("source")) {
    provenance["capture"] = material.provenance["source"];
  }
  if (material.provenance.contains("software")) {
    provenance["reconstructed_by"] = material.provenance["software"];
  }
  scene.extras = {{"brdfrig", provenance}};
  brdf::WriteGltfFile(output, scene);
  return summary;
}

}  // namespace brdfrig::reconstruct
