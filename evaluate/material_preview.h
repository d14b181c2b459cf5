// The first thing a report shows: the material itself on the sphere test's sphere under its
// lights (evaluate/sphere_test.h, same protocol and numbers), one row per model:
//   simulated captures — the truth (the scene's BRDF), then the fit with its PSNR against it;
//   hardware captures — no truth: the fit's spheres, and beside them the validation photos with
//     the fit's prediction and its PSNR (figures.validation_photos, drawn by the section);
//   the glTF version of the material, when there is one, in a row of its own with its PSNR
//     against the truth (without a truth: against the fit, the loss of the conversion).
// report.json: "figures": {"preview": {...}}; the images under preview/.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "brdf/brdf.h"
#include "brdf/material_file.h"
#include "evaluate/report.h"
#include "evaluate/sphere_test.h"

namespace brdfrig::evaluate {

struct PreviewModels {
  const brdf::Brdf* truth = nullptr;  // null: a hardware capture
  const brdf::Brdf* fit = nullptr;    // required
  std::string fit_label;              // e.g. "fit (microfacet)"
  const brdf::Brdf* gltf = nullptr;   // null: no glTF version (say why in gltf_note)
  std::string gltf_note;
  std::string gltf_file;  // the exported .glb beside the report, when there is one
};

// The glTF version of a fitted material, or null with the reason in `why_not`.
std::shared_ptr<const brdf::Brdf> GltfVersionOf(const brdf::Material& material,
                                                std::string* why_not);

// Renders the rows (SphereTest with `sphere` options, images kept) and writes the images under
// report_dir/preview/. Throws brdfrig::Error without a fit.
nlohmann::json MaterialPreviewJson(const PreviewModels& models, const SphereTestOptions& sphere,
                                   const std::filesystem::path& report_dir);

// The report's first section: the sphere grid (models × lights, PSNR under each image) and,
// when `validation_photos` is given (figures.validation_photos; `validation_photos_gltf` the
// glTF version's figures, may be null), a grid of the photos beside the fit's prediction.
ReportSection MaterialPreviewSection(const nlohmann::json& preview,
                                     const nlohmann::json* validation_photos,
                                     const nlohmann::json* validation_photos_gltf);

}  // namespace brdfrig::evaluate
