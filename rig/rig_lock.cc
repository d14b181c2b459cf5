#include "rig/rig_lock.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <system_error>

#include "common/error.h"
#include "common/sha256.h"
#include "common/yaml_reader.h"

namespace brdfrig::rig {
namespace {

namespace fs = std::filesystem;

// A path as the kernel sees it, so that two spellings of one file are one endpoint.
std::string Canonical(const fs::path& base, const std::string& path) {
  const fs::path p = fs::path(path).is_absolute() ? fs::path(path) : base / path;
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(p, error);
  return (error ? p.lexically_normal() : canonical).string();
}

std::string EndpointOf(const YamlNode& settings, const std::string& device,
                       const fs::path& rig_file) {
  const fs::path base = rig_file.parent_path();
  const std::string backend = settings.Get("backend", "");
  if (settings.Has("transport")) {
    const std::string transport = settings.Get("transport", "");
    if (transport == "tcp") {
      return "modbus-tcp:" + settings.Get("host", "") + ":" +
             std::to_string(settings.Get("port", 502));
    }
    if (transport == "rtu") return "modbus-rtu:" + Canonical(base, settings.Get("device", ""));
  }
  if (backend == "gphoto2") {
    if (settings.Has("port")) return "gphoto2:" + settings.Get("port", "");
    if (settings.Has("model")) return "gphoto2:" + settings.Get("model", "");
    return "gphoto2:any";
  }
  if (settings.Has("scene")) {
    // A simulated device is its scene's device of that name (sim axes may say `axis:`).
    const std::string name = settings.Has("axis") && settings.Required("axis").IsScalar()
                                 ? settings.Get("axis", "")
                                 : device;
    return backend + ":" + Canonical(base, settings.Get("scene", "")) + "#" + name;
  }
  return backend + ":" + Canonical(fs::current_path(), rig_file.string()) + "#" + device;
}

}  // namespace

std::vector<DeviceEndpoint> RigEndpoints(const fs::path& rig_file) {
  const YamlNode root = LoadYamlFile(rig_file.string());
  std::map<std::string, std::string> by_endpoint;  // endpoint -> devices using it
  auto add = [&](const YamlNode& settings, const std::string& device, const std::string& name) {
    if (!settings.IsMap()) return;  // ReadRigDescription reports the shape
    std::string& devices = by_endpoint[EndpointOf(settings, name, rig_file)];
    devices += (devices.empty() ? "" : ", ") + device;
  };
  if (const auto camera = root.Optional("camera")) add(*camera, "camera", "camera");
  if (const auto axes = root.Optional("axes"); axes && axes->IsMap()) {
    for (const std::string& name : axes->Keys()) add(axes->Required(name), "axis " + name, name);
  }
  if (const auto light = root.Optional("light")) add(*light, "light", "light");
  std::vector<DeviceEndpoint> endpoints;
  for (const auto& [endpoint, devices] : by_endpoint) endpoints.push_back({devices, endpoint});
  return endpoints;
}

fs::path LockDirectory() {
  if (const char* dir = std::getenv("BRDFRIG_LOCK_DIR"); dir != nullptr && *dir != '\0') {
    fs::create_directories(dir);
    return dir;
  }
  // Shared by every user of the machine: the rig is one rig whoever runs the command.
  const fs::path shared = "/run/lock/brdfrig";
  std::error_code error;
  if (fs::is_directory("/run/lock") && ::access("/run/lock", W_OK) == 0) {
    if (fs::create_directory(shared, error)) ::chmod(shared.c_str(), 01777);
    if (fs::is_directory(shared) && ::access(shared.c_str(), W_OK) == 0) return shared;
  }
  const fs::path own = fs::temp_directory_path() / ("brdfrig-locks-" + std::to_string(::getuid()));
  fs::create_directories(own);
  return own;
}

fs::path LockFile(const std::string& kind, const std::string& key) {
  return LockDirectory() / (kind + "-" + Sha256Hex(key).substr(0, 24) + ".lock");
}

RigLock RigLock::Acquire(const fs::path& rig_file) {
  const std::vector<DeviceEndpoint> endpoints = RigEndpoints(rig_file);
  RigLock lock;
  // Sorted by endpoint, so two processes asking for overlapping sets cannot each hold half
  // (and no lock is waited for anyway: the second owner fails at once).
  for (const DeviceEndpoint& e : endpoints) {
    const fs::path file = LockFile("device", e.endpoint);
    lock.locks_.push_back(
        FileLock::Acquire(file, "the rig's " + e.device + " (" + e.endpoint + ")"));
  }
  return lock;
}

}  // namespace brdfrig::rig
