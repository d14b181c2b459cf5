// The light calibration file (`brdfrig rig calibrate light` writes it; rig.yaml references it
// as `calibration: {light: FILE}`): where the light stands with every axis at rest, measured
// from a mirror tile's highlights, replacing the geometry's nominal `light.position` — and the
// highlight's nudge in the reconstruction, which then takes the light as measured. JSON:
//
//   {"format": "brdfrig-light-calibration", "version": 1, "created": "2026-...Z",
//    "software": "brdfrig 0.1.0", "light_position": [x, y, z],    (metres, world, at rest)
//    "nominal_offset_m": 0.005, "rms_miss_m": 0.0001, "dilution": 6.2,
//    "photos": [{"photo": "...", "positions_deg": {...}, "highlight_px": [x, y],
//                "miss_m": 0.0001}, ...]}
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "geometry/camera.h"

namespace brdfrig::geometry {

struct LightCalibrationPhoto {
  std::string photo;
  std::map<std::string, double> positions_deg;  // where the axes stood (degrees, for people)
  double highlight_x = 0, highlight_y = 0;      // the highlight's centre (pixels)
  double miss_m = 0;  // distance of the fitted light from this photo's reflected ray
};

struct LightCalibration {
  std::string created;  // ISO 8601, UTC
  std::string software;
  Vec3 light_position = Vec3::Zero();  // what the reconstruction uses (world, at rest, metres)
  double nominal_offset_m = 0;         // how far it is from the rig file's nominal light
  double rms_miss_m = 0;               // RMS over the photos of miss_m
  // How much less certain the position is than each photo's ray, in its worst-determined
  // direction (the triangulation's geometry; 1 = as certain as one ray).
  double dilution = 0;
  std::vector<LightCalibrationPhoto> photos;
};

void WriteLightCalibration(const std::filesystem::path& path, const LightCalibration& c);
// Throws FileError naming the file and the field: another format, a missing field, a position
// not finite or not above the sample plane.
LightCalibration ReadLightCalibration(const std::filesystem::path& path);

}  // namespace brdfrig::geometry
