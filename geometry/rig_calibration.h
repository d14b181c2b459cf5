// The calibrations rig.yaml references, `calibration: {lens: FILE, flat: FILE, white: FILE,
// light: FILE}` (docs/calibration.md), and what applying them changes: the lens calibration
// replaces the geometry's intrinsics (geometry/lens_calibration_file.h), the white reference its
// paper albedo (geometry/white_reference_file.h), the light calibration its light's rest position
// (geometry/light_calibration_file.h; the reconstruction then no longer moves the light to the
// highlight), and the flat field — a gain map, EXR, mean 1 — divides each merged photo in the
// reconstruction (reconstruct/measure_position.h). A session keeps a copy of
// each in its rig snapshot (session/rig_snapshot.h), so it is reconstructed with the
// calibrations it was captured with.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace brdfrig::geometry {

struct RigGeometry;

struct RigCalibrationFiles {
  std::filesystem::path lens, flat, white, light;  // empty: nominal

  bool Empty() const;
  // For material.json's provenance: each calibration's file and SHA-256, or "nominal".
  nlohmann::json Provenance() const;
  // "lens, flat field" ... ; "" when nothing is nominal.
  std::string NominalOnes() const;
};

// Every calibration, in the order they are listed and done: its key under rig.yaml's
// `calibration:`, its name for people, its role in a session's rig snapshot, and its file.
struct CalibrationKind {
  const char* key;
  const char* name;
  const char* snapshot_role;
  std::filesystem::path RigCalibrationFiles::*file;
};
inline constexpr std::array<CalibrationKind, 4> kCalibrationKinds = {{
    {"lens", "lens", "lens_calibration", &RigCalibrationFiles::lens},
    {"flat", "flat field", "flat_field", &RigCalibrationFiles::flat},
    {"white", "white reference", "white_reference", &RigCalibrationFiles::white},
    {"light", "light", "light_calibration", &RigCalibrationFiles::light},
}};

// Applies the lens, white and light calibrations to `geometry` (the flat field is the
// measurement's, reconstruct/gain_map.h; the callers have checked that each file is there). Throws
// FileError naming the calibration file: unreadable or malformed, or of another camera
// (`camera_model` as rig.yaml names it, "" when it does not).
void ApplyRigCalibration(const RigCalibrationFiles& files, const std::string& camera_model,
                         RigGeometry* geometry);

}  // namespace brdfrig::geometry
