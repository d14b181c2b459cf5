// rig.yaml: which backend drives each device, with its settings, plus the rig's nominal
// geometry. The one place a rig is assembled from configuration, for `brdfrig rig`, the run
// engine and the daemon alike:
//
//   geometry: scenes/default.yaml     # a file whose `rig:` section is the geometry, or inline:
//   # geometry: {camera: {...}, light: {...}, axes: [...], target: {...}}
//   camera: {backend: gphoto2, model: "Nikon D750"}
//   axes:
//     light_arm: {backend: modbus, transport: tcp, host: 192.168.0.20, slave: 1,
//               profile: oriental_az_direct}   # keys: docs/rig.md
//     camera_arm: {backend: sim, scene: scenes/default.yaml}
//   light: {backend: sim, scene: scenes/default.yaml}          # optional (switched light)
//   calibration: {lens: calibration/lens.json,   # optional, each: measured values replace the
//                 flat: calibration/flat.exr,    # nominal ones (`brdfrig rig calibrate lens|
//                 white: calibration/white.json} # flat|white`, geometry/rig_calibration.h)
//   changed: 2026-11-30   # optional: when the rig last changed (lamp, lens, arm moved); older
//                         # calibrations are stale (`brdfrig rig calibrate status`)
//
// Relative paths are relative to the rig file's directory. Every axis named under `axes` must
// exist in the geometry. Errors name file:line:column.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "geometry/rig_geometry.h"
#include "rig/axis.h"
#include "rig/camera.h"
#include "rig/rig_lock.h"

namespace brdfrig::rig {

struct Rig {
  // First member, so destroyed last: the devices are closed before another owner may open them.
  RigLock lock;
  geometry::RigDescription description;
  std::unique_ptr<Camera> camera;
  std::map<std::string, std::unique_ptr<Axis>> axes;  // by axis name
  std::unique_ptr<Light> light;                       // null when the rig has none
};

// Reads rig.yaml's geometry and checks the device sections' shape (every device has a
// `backend`, every axis exists in the geometry) without opening devices; a device's own settings
// are validated by its backend when it is opened.
geometry::RigDescription ReadRigDescription(const std::filesystem::path& rig_file);

// Reads rig.yaml, takes the rig's lock (rig_lock.h: a second owner fails here, naming the
// holder, before any device is opened) and opens every device through the backend registry
// (backends must have been registered first, e.g. sim::RegisterSimBackends()). Throws FileError for
// configuration errors and CameraError/AxisError for devices that cannot be opened.
Rig OpenRig(const std::filesystem::path& rig_file);
// The same with the rig's lock already taken (RigLock::Acquire(rig_file)), for callers that
// must own the rig before they touch anything else (a session to resume).
Rig OpenRig(const std::filesystem::path& rig_file, RigLock held);

// Opens only the axes of rig.yaml, without the rig's lock and without its camera or light: for
// a process that watches where the drives are while another one owns and moves the rig (it
// must only read them). Throws like OpenRig.
std::map<std::string, std::unique_ptr<Axis>> OpenRigAxes(const std::filesystem::path& rig_file);

}  // namespace brdfrig::rig
