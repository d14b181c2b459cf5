#include "simcamera/drive_positions.h"

#include "rig/rig_file.h"

namespace brdfrig::simcamera {

DrivePositions::DrivePositions(const std::filesystem::path& rig_file)
    : axes_(rig::OpenRigAxes(rig_file)) {}

geometry::AxisPositions DrivePositions::Read() {
  geometry::AxisPositions positions;
  for (auto& [name, axis] : axes_) {
    const rig::AxisStatus status = axis->Status();
    if (status.state == rig::AxisState::kDisconnected) {
      throw rig::AxisError(
          rig::AxisError::Kind::kCommunication, 0,
          "the simulated camera cannot read axis '" + name + "': " + status.message);
    }
    positions[name] = status.position;
  }
  return positions;
}

}  // namespace brdfrig::simcamera
