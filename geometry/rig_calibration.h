// The calibrations rig.yaml references, `calibration: {lens: FILE, flat: FILE, white: FILE}`
// (docs/calibration.md), and what applying them changes: the lens calibration replaces the
// geometry's intrinsics (geometry/lens_calibration_file.h), the white reference its paper albedo
// (geometry/white_reference_file.h), and the flat field — a gain map, EXR, mean 1 — divides each
// merged photo in the reconstruction (reconstruct/measure_position.h). A session keeps a copy of
// each in its rig snapshot (session/rig_snapshot.h), so it is reconstructed with the
// calibrations it was captured with.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace brdfrig::geometry {

struct RigGeometry;

struct RigCalibrationFiles {
  std::filesystem::path lens, flat, white;  // empty: nominal

  bool Empty() const { return lens.empty() && flat.empty() && white.empty(); }
  // For material.json's provenance: each calibration's file and SHA-256, or "nominal".
  nlohmann::json Provenance() const;
  // "lens, flat field" ... ; "" when nothing is nominal.
  std::string NominalOnes() const;
};

// Applies the lens and white calibrations to `geometry` (the flat field is the measurement's,
// reconstruct/gain_map.h; the callers have checked that each file is there). Throws FileError
// naming the calibration file: unreadable or malformed, or of another camera
// (`camera_model` as rig.yaml names it, "" when it does not).
void ApplyRigCalibration(const RigCalibrationFiles& files, const std::string& camera_model,
                         RigGeometry* geometry);

}  // namespace brdfrig::geometry
