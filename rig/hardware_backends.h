// Registers the real device backends with rig/backend_registry.h:
//   axis  `backend: modbus`  (rig/modbus_axis.h; keys in docs/rig.md)
//   light `backend: modbus`  (rig/modbus_light.h)
//   camera `backend: gphoto2` (rig/gphoto2_camera.h)
// Safe to call more than once.
#pragma once

namespace brdfrig::rig {

void RegisterHardwareBackends();

}  // namespace brdfrig::rig
