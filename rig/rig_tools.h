// The manual-check commands behind `brdfrig rig check|move|shoot`: library functions so that
// tests call exactly what the command line runs. Each opens only the devices it needs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rig/axis.h"

namespace brdfrig::rig {

struct DeviceCheck {
  std::string name;     // "camera", an axis name, "light"
  std::string backend;  // as in rig.yaml
  bool ok = false;
  std::string detail;  // model/port/firmware/position, or why it failed
};

struct RigCheckReport {
  std::filesystem::path rig_file;
  std::vector<DeviceCheck> devices;
  bool ok() const;
  std::string ToString() const;  // one line per device and a summary line
};

// Reads rig.yaml (configuration errors throw FileError with file:line), then opens every
// configured device independently and reports what it finds; a device that cannot be opened
// or reports an alarm makes the report not ok, with the reason, and does not stop the others
// from being checked.
RigCheckReport CheckRig(const std::filesystem::path& rig_file);

// Moves one configured axis to `angle_deg` (degrees: this is a person's command).
MoveReport MoveAxis(const std::filesystem::path& rig_file, const std::string& axis,
                    double angle_deg);

struct ShootReport {
  double exposure_s = 0;  // exposure actually used (nearest the camera offers)
  std::vector<std::filesystem::path> files;
  std::string ToString() const;
};

// Sets the exposure ("1/60", "0.5"), takes one shot and writes its files: the first to
// `output`, further ones (RAW+JPEG) next to it with their own extensions.
ShootReport Shoot(const std::filesystem::path& rig_file, const std::string& exposure,
                  const std::filesystem::path& output);

}  // namespace brdfrig::rig
