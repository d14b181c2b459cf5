// The white reference file (`brdfrig rig calibrate white` writes it; rig.yaml references it as
// `calibration: {white: FILE}`): the paper's albedo measured against a tile of certified
// reflectance, replacing the geometry's nominal `target.paper_albedo`. JSON:
//
//   {"format": "brdfrig-white-reference", "version": 1, "created": "2026-...Z",
//    "software": "brdfrig 0.1.0", "paper_albedo": 0.75, "reference_albedo": 0.5,
//    "tile_spread": 0.004, "per_photo": [...], "flat_field": "flat.exr", "photos": [...]}
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfrig::geometry {

struct WhiteReference {
  std::string created;  // ISO 8601, UTC
  std::string software;
  double paper_albedo = 0;      // what the reconstruction uses
  double reference_albedo = 0;  // the tile's certified reflectance
  double tile_spread = 0;       // worst relative standard deviation on the tile
  std::vector<double> per_photo;
  std::string flat_field;  // the gain map the photos were divided by ("" = none)
  std::vector<std::string> photos;
};

void WriteWhiteReference(const std::filesystem::path& path, const WhiteReference& reference);
// Throws FileError naming the file and the field: another format, a missing field, an albedo
// outside (0, 1] or not finite.
WhiteReference ReadWhiteReference(const std::filesystem::path& path);

}  // namespace brdfrig::geometry
