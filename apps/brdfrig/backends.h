// The device backends the `brdfrig` command knows: the simulator and the real hardware. The
// acquire library never names them (DESIGN.md: the backend is chosen from configuration).
#pragma once

#include "rig/hardware_backends.h"
#include "sim/devices.h"

namespace brdfrig::apps {

inline void RegisterBackends() {
  sim::RegisterSimBackends();
  rig::RegisterHardwareBackends();
}

}  // namespace brdfrig::apps
