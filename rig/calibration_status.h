// `brdfrig rig calibrate status`: which of the rig's values are measured and which nominal,
// when each calibration was made and with what error, and which calibrations are older than
// the rig's last change (rig.yaml `changed:`), so no longer describe it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfrig::rig {

struct CalibrationState {
  std::string name;            // "lens", "flat field", "white reference"
  std::filesystem::path file;  // empty: the nominal values are used
  std::string created;         // ISO 8601 UTC, as the file says ("" when it does not)
  std::string figure;          // the calibration's own error, for people
  // Made before the rig's last change, or of unknown age when rig.yaml says when it changed.
  bool stale = false;
};

struct CalibrationStatus {
  std::filesystem::path rig_file;
  std::string rig_changed;  // rig.yaml `changed:`; "" when not said
  std::vector<CalibrationState> calibrations;

  // Every calibration present, none stale.
  bool Current() const;
  std::string ToString() const;  // a table, one line per calibration, and what to do
};

// Reads rig.yaml and the calibration files it references. Throws FileError for a rig.yaml or a
// calibration that cannot be read (the same refusal every other command gives).
CalibrationStatus ReadCalibrationStatus(const std::filesystem::path& rig_file);

}  // namespace brdfrig::rig
