// Where the rig's axes are, read from their drives like any client does: the axes of a rig
// file (typically Modbus drives over TCP, e.g. `brdfrig rig simdrive`) opened without taking
// the rig's lock, so the simulated camera photographs the pose the capture moved the drives to.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "geometry/rig_geometry.h"
#include "rig/axis.h"

namespace brdfrig::simcamera {

class DrivePositions {
 public:
  // Opens the axes of `rig_file` through the backend registry (backends must be registered).
  explicit DrivePositions(const std::filesystem::path& rig_file);
  // Each axis's position as its drive reports it (radians). Throws rig::AxisError when a
  // drive does not answer: a camera cannot photograph an unknown pose.
  geometry::AxisPositions Read();

 private:
  std::map<std::string, std::unique_ptr<rig::Axis>> axes_;
};

}  // namespace brdfrig::simcamera
