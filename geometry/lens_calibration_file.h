// The lens calibration file (`brdfrig rig calibrate lens` writes it; rig.yaml references it as
// `calibration: {lens: FILE}`): what the lab measured about its camera's intrinsics, with the
// evidence (board, photos, errors) and when. JSON:
//
//   {"format": "brdfrig-lens-calibration", "version": 1, "created": "2026-...Z",
//    "software": "brdfrig 0.1.0", "camera": {"model": "...", "serial": "..."},
//    "board": {...}, "settings": {...},
//    "intrinsics": {"width", "height", "fx", "fy", "cx", "cy", "k1", "k2"},
//    "uncertainty": {"fx", "fy", "cx", "cy", "k1", "k2"},     (one standard deviation)
//    "errors": {"rms_px", "coverage", "corners",
//               "photos": [{"photo", "corners", "rms_px", "edge_width_px"}, ...]}}
//
// It lives in geometry/ (not calibrate/) because every reader of a rig — rig/, and a session's
// snapshot — must be able to apply it without OpenCV's calibration code.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geometry/camera.h"

namespace brdfrig::geometry {

struct PhotoCalibrationError {
  std::string photo;
  int corners = 0;
  double rms_px = 0;         // reprojection error of this photo's corners
  double edge_width_px = 0;  // sharpness: how many pixels a black-to-white edge takes
};

struct LensCalibration {
  std::string created;  // ISO 8601, UTC
  std::string software;
  std::string camera_model, camera_serial;  // "" when not known
  nlohmann::json board = nlohmann::json::object();
  nlohmann::json settings = nlohmann::json::object();
  Intrinsics intrinsics;   // width, height = the photos' size
  Intrinsics uncertainty;  // standard deviations of fx .. k2 (width, height unused)
  double rms_px = 0;
  double coverage = 0;  // fraction of the frame's grid cells holding a corner
  int corners = 0;
  std::vector<PhotoCalibrationError> photos;

  nlohmann::json ToJson() const;
};

void WriteLensCalibration(const std::filesystem::path& path, const LensCalibration& calibration);
// Throws FileError naming the file and the field for anything missing, non-finite or
// implausible (focal lengths <= 0, a principal point outside the image).
LensCalibration ReadLensCalibration(const std::filesystem::path& path);

// The rig's intrinsics with a calibration applied. Refuses (FileError naming `source`) a
// calibration of another camera: a different image size than the rig's resolution, or a
// different camera model when both name one.
Intrinsics ApplyLensCalibration(const LensCalibration& calibration,
                                const std::filesystem::path& source, const Intrinsics& nominal,
                                const std::string& rig_camera_model);

}  // namespace brdfrig::geometry
