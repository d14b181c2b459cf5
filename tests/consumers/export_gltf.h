// The file a consumer test reads: glTF parameters written as a material.json of kind gltf and
// exported to .glb through the real `brdfrig export` (BRDFRIG_BINARY, set by the test's CMake).
#pragma once

#include <filesystem>
#include <string>

#include "brdf/gltf_model.h"
#include "brdf/material_file.h"
#include "tests/common/run_brdfrig.h"

namespace brdfrig::testing {

// dir/name.glb; `result` gets the export's exit status and output (status 0 on success).
inline std::filesystem::path ExportGltfMaterial(const brdf::GltfParams& params,
                                                const std::filesystem::path& dir,
                                                const std::string& name, CommandResult* result) {
  brdf::Material material;
  material.kind = brdf::ModelKind::kGltf;
  material.gltf = params;
  const std::filesystem::path json = dir / (name + ".json"), glb = dir / (name + ".glb");
  brdf::WriteMaterialFile(json, material);
  *result = RunBrdfrig("export '" + json.string() + "' -o '" + glb.string() + "'");
  return glb;
}

}  // namespace brdfrig::testing
