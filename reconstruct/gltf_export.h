// `brdfrig export material.json -o tile.glb|tile.gltf`: any material as a glTF 2.0 file
// (brdf/gltf_file.h). The material's glTF version is the one reconstruct wrote beside the
// chosen rung (material.json's "gltf" and "gltf_fit"); a material without one (older files,
// hand-written or edited ones, a measured nbrdf fit, a MERL table) is fitted here, over the
// whole hemisphere (reconstruct/gltf_fit.h). The tile has the capture's cut-out size
// (provenance.cutout_m); without one the default rig's 0.1 m × 0.1 m, and the extras say which.
#pragma once

#include <filesystem>
#include <string>

#include "brdf/gltf_model.h"
#include "reconstruct/gltf_fit.h"

namespace brdfrig::reconstruct {

struct GltfExportSummary {
  std::string source_kind;  // the material's kind ("ggx", ..., "nbrdf", "merl")
  bool fitted_now = false;  // no glTF version in the file: fitted by the export
  brdf::GltfParams params;
  double sphere_vs_model_db = 0;  // mean sphere PSNR of the export against the material
  double tile_width_m = 0, tile_height_m = 0;
  std::string ToString() const;  // one line
};

// Throws FileError naming the material or the output (nothing written).
GltfExportSummary ExportGltfFile(const std::filesystem::path& material,
                                 const std::filesystem::path& output,
                                 const GltfFitOptions& options = {});

}  // namespace brdfrig::reconstruct
