// A material as a glTF 2.0 file (docs/gltf.md): the `gltf` kind's parameters as core
// pbrMetallicRoughness plus KHR_materials_ior and KHR_materials_specular, on two preview nodes
// (a UV sphere and the flat sample tile at its size), with the provenance in the material's
// `extras`. `.glb` writes the binary container; `.gltf` writes the JSON with its buffer in a
// `.bin` beside it (same stem). Written with nlohmann::json: the format is small enough that a
// glTF library would add a dependency and no checking the Khronos validator does not do
// (tests/export/gltf_validator_test.cc runs it on every kind).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "brdf/gltf_model.h"

namespace brdfrig::brdf {

struct GltfScene {
  GltfParams material;
  std::string name = "material";  // the material's and the file's name in viewers
  double tile_width_m = 0.1;      // the flat sample tile (glTF units are metres)
  double tile_height_m = 0.1;
  nlohmann::json extras = nlohmann::json::object();  // the material's extras (provenance)
  int sphere_segments = 64, sphere_rings = 32;       // UV sphere tessellation
  void Validate() const;                             // throws brdfrig::Error naming the field
};

// The glTF document and its binary buffer; `buffer_uri` empty for .glb (the buffer is the
// GLB's BIN chunk), else the .bin's file name.
struct GltfDocument {
  nlohmann::json json;
  std::string buffer;
};
GltfDocument BuildGltf(const GltfScene& scene, const std::string& buffer_uri);

// By the extension of `output`: .glb or .gltf (+ .bin). Atomic; throws FileError naming the
// output, writing nothing, when a value is not finite (the writer's own check) or the extension
// is neither.
void WriteGltfFile(const std::filesystem::path& output, const GltfScene& scene);

// The GLB container (header, JSON chunk padded with spaces, BIN chunk padded with zeros).
std::string PackGlb(const GltfDocument& document);

}  // namespace brdfrig::brdf
