// One owner of the rig: before any device is opened, the process takes an exclusive lock per
// device endpoint (the camera, each drive's bus or gateway, the light). Two daemons, or a
// daemon and a foreground `capture`, would otherwise move the same axes and shoot frames
// mid-move that are recorded as good. The second owner fails at once, naming the holder, and
// opens nothing.
//
// Endpoints are derived from the device settings in rig.yaml, so two rig files that name the
// same hardware conflict too:
//   modbus, transport tcp   modbus-tcp:HOST:PORT        (one lock per gateway, all slaves)
//   modbus, transport rtu   modbus-rtu:/dev/real/path   (one lock per serial bus)
//   gphoto2                 gphoto2:PORT, else gphoto2:MODEL, else gphoto2:any (autodetect)
//   sim                     sim:/canonical/scene.yaml#DEVICE
//   any other backend       BACKEND:/canonical/rig.yaml#DEVICE
// Lock files live in BRDFRIG_LOCK_DIR when set, else /run/lock/brdfrig (shared by every user),
// else <tmp>/brdfrig-locks-UID.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/file_lock.h"

namespace brdfrig::rig {

struct DeviceEndpoint {
  std::string device;    // "camera", "axis light_arm", "light"
  std::string endpoint;  // e.g. "modbus-tcp:192.168.0.20:502"
};

// The endpoints of every device in rig.yaml (shared endpoints listed once, sorted).
std::vector<DeviceEndpoint> RigEndpoints(const std::filesystem::path& rig_file);

std::filesystem::path LockDirectory();
// The lock file for one thing in LockDirectory(): "<kind>-<hash of key>.lock".
std::filesystem::path LockFile(const std::string& kind, const std::string& key);

// Holds one lock per endpoint; released when destroyed (or when the process dies).
class RigLock {
 public:
  RigLock() = default;
  // Throws brdfrig::Error naming the device, its endpoint and the holder (pid, command).
  static RigLock Acquire(const std::filesystem::path& rig_file);

 private:
  std::vector<FileLock> locks_;
};

}  // namespace brdfrig::rig
