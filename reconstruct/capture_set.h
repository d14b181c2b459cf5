// What the reconstruction reads: per capture position the bracket's photo files with their
// exposure times, plus the rig's nominal geometry (intrinsics, target, nominal light) used only
// as starting values and for the light's distance. How the photos were stored (a session
// directory, `brdfrig simulate` output) is the loader's business.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::reconstruct {

struct BracketFrame {
  std::filesystem::path file;
  double exposure_s = 0;
  // SHA-256 recorded when the frame was captured (hex); "" when the source records none.
  // The reconstruction checks it before using the photo.
  std::string sha256;
};

struct CapturePosition {
  int index = 0;
  geometry::AxisPositions axis_readings;  // as the rig reported them (radians)
  std::vector<BracketFrame> frames;       // any order; sorted by exposure when merged
  // A validation position of the plan: captured like the rest, never fitted (the result lists
  // it for the comparison of its photos with the fit's rendering).
  bool validation = false;
};

struct CaptureSet {
  std::string name;               // for reports, e.g. the session directory
  geometry::RigGeometry nominal;  // intrinsics, target, nominal light geometry
  std::vector<CapturePosition> positions;
  std::vector<std::string> warnings;  // what the loader left out, and why
  // Positions the loader could not use (e.g. a bracket the run stopped inside): reported by
  // the reconstruction as dropped, like a position whose photos are unreadable.
  struct LeftOut {
    int index = 0;
    std::string reason;
  };
  std::vector<LeftOut> left_out;
  // The rig's calibrations, already applied to `nominal` but the flat field, which the
  // measurement applies (sessions: from the rig snapshot). nullopt where the geometry is the
  // scene's own truth (`brdfrig simulate` output), which needs none.
  std::optional<geometry::RigCalibrationFiles> calibration;
};

// Reads the photos/capture.json written by `brdfrig simulate` (or `brdfrig capture --sim`),
// with the nominal geometry from the scene file it names. Throws FileError for a malformed
// file (a negative position_index included), a missing photo or a missing scene.
CaptureSet LoadSimulatedCapture(const std::filesystem::path& dir);

// Reads an acquisition session (session.sqlite) through session::ReadSession, with the nominal
// geometry from the session's own rig snapshot. Only positions whose bracket is complete are
// used (an interrupted session's last position is left out with a warning); where a shot gave
// RAW + JPEG, the RAW file is used. Throws brdfrig::Error when the session cannot be read.
CaptureSet LoadSessionCapture(const std::filesystem::path& dir);

}  // namespace brdfrig::reconstruct
