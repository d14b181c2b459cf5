// material.json: a fitted model of one kind of the model ladder plus how it was obtained.
//   {"format": "brdfrig-material", "version": 2,
//    "kind": "seed" | "seed_constrained" | "microfacet" | "ggx" | "beckmann" | "prior" | "gltf",
//    "slices": [{"theta_in": .., "red": {"A1":..,"A2":..,"h":..,"x0":..}, "green": .., "blue": ..,
//                "diagnostics": {...}}, ...],                      (seed kinds)
//    "microfacet": {"diffuse": [r,g,b], "f0": [r,g,b], "alpha": .., "fresnel_knots": [..],
//                   "log_d": [..], "max_theta_h": .., "shadowing_alpha": ..},  (microfacet kinds)
//    "table": {"grid": {"theta_h": 64, "theta_d": 32, "phi_d": 8, "epsilon": .., "cos_floor": ..},
//              "encoding": "uint16-base64", "offset": .., "scale": ..,
//              "red": "<base64>", "green": .., "blue": ..},              (prior: a Rusinkiewicz
//              table, brdf/rusinkiewicz_table.h; q = offset + scale · u per little-endian uint16 u)
//    "gltf": {"base_color": [r,g,b], "metallic": .., "roughness": .., "ior": .., "specular": ..,
//             "specular_color": [r,g,b]},     (kind gltf: the model, brdf/gltf_model.h; any other
//              kind: optional, the material's glTF version written by reconstruct beside it)
//    "gltf_fit": {...},                        (optional: how "gltf" was obtained, its figures)
//    "fit": {...}, "ladder": [...], "provenance": {...}}
// Version 1 files ({"format": "brdfrig-slices", "version": 1, "slices": ..}) still load, as
// kind "seed". Reading validates everything and names the offending field, e.g.
//   "material.json: slices[2].green.h: must be > 0, got -0.01".
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "brdf/gltf_model.h"
#include "brdf/microfacet_model.h"
#include "brdf/rusinkiewicz_table.h"
#include "brdf/slice_model.h"

namespace brdfrig::brdf {

// How well one slice is supported by its data (written by the fit; optional on read).
struct SliceDiagnostics {
  double residual = 0;                            // robust RMS of the fit residuals
  int sample_count = 0;                           // BRDF samples used
  double theta_min = 0, theta_max = 0;            // theta range covered by the samples (radians)
  std::array<std::array<double, 4>, 3> stddev{};  // per channel: A1, A2, h, x0 (NaN = unknown)
  bool has_stddev = false;
  std::vector<std::string> warnings;  // e.g. "A2 unobserved: shared across slices"
};

// The rungs of the model ladder (docs/design.md): the seed's slices, the same slices with one
// shared diffuse level and energy conservation, the data-driven microfacet model, the
// analytic baselines, and the measured prior's table (prior/). Beside them the glTF 2.0
// metal-rough BRDF (`gltf`, brdf/gltf_model.h): not a rung, the form a material takes when it
// is exported (docs/gltf.md).
enum class ModelKind { kSeed, kSeedConstrained, kMicrofacet, kGgx, kBeckmann, kPrior, kGltf };
inline constexpr ModelKind kLadderModelKinds[] = {
    ModelKind::kSeed, ModelKind::kSeedConstrained, ModelKind::kMicrofacet,
    ModelKind::kGgx,  ModelKind::kBeckmann,        ModelKind::kPrior};
inline constexpr ModelKind kAllModelKinds[] = {
    ModelKind::kSeed,     ModelKind::kSeedConstrained, ModelKind::kMicrofacet, ModelKind::kGgx,
    ModelKind::kBeckmann, ModelKind::kPrior,           ModelKind::kGltf};
const char* ModelKindName(ModelKind kind);
// Throws brdfrig::Error listing the kinds for an unknown name.
ModelKind ParseModelKind(const std::string& name);
bool IsSliceKind(ModelKind kind);

struct Material {
  ModelKind kind = ModelKind::kSeed;
  std::vector<Slice> slices;                  // slice kinds: sorted by theta_in
  std::vector<SliceDiagnostics> diagnostics;  // slice kinds: empty, or one per slice
  MicrofacetModelParams microfacet;           // microfacet kinds (distribution matches kind)
  RusinkiewiczGrid table_grid;                // prior: the table's grid and values
  TableValues table;
  // Kind gltf: the model. Any other kind: its glTF version (reconstruct/gltf_fit.h), if written.
  std::optional<GltfParams> gltf;
  nlohmann::json gltf_fit = nlohmann::json::object();  // how `gltf` was obtained, its figures
  nlohmann::json fit = nlohmann::json::object();       // the fit's diagnostics (non-slice kinds)
  nlohmann::json ladder = nlohmann::json::array();     // every rung's validation scores
  nlohmann::json provenance = nlohmann::json::object();

  // The model as a BRDF, whatever its kind (validates).
  std::shared_ptr<const Brdf> Model() const;
  // Slice kinds only (throws brdfrig::Error otherwise).
  SliceModel Slices() const;
};

Material ParseMaterial(const std::string& json_text, const std::string& source_name);
Material ReadMaterialFile(const std::filesystem::path& path);
std::string SerializeMaterial(const Material& material);  // deterministic, stable key order
void WriteMaterialFile(const std::filesystem::path& path, const Material& material);

}  // namespace brdfrig::brdf
