// material.json: the fitted slice model plus how it was obtained.
//   {"format": "brdfrig-slices", "version": 1,
//    "slices": [{"theta_in": .., "red": {"A1":..,"A2":..,"h":..,"x0":..}, "green": .., "blue": ..,
//                "diagnostics": {...}}, ...],
//    "provenance": {...}}
// Reading validates everything and names the offending field, e.g.
//   "material.json: slices[2].green.h: must be > 0, got -0.01".
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

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

struct Material {
  std::vector<Slice> slices;                  // sorted by theta_in
  std::vector<SliceDiagnostics> diagnostics;  // empty, or one per slice
  nlohmann::json provenance = nlohmann::json::object();

  SliceModel Model() const { return SliceModel(slices); }
};

Material ParseMaterial(const std::string& json_text, const std::string& source_name);
Material ReadMaterialFile(const std::filesystem::path& path);
std::string SerializeMaterial(const Material& material);  // deterministic, stable key order
void WriteMaterialFile(const std::filesystem::path& path, const Material& material);

}  // namespace brdfrig::brdf
