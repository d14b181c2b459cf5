// Device backends register a constructor under a name; rig.yaml names the backend of each
// device (`backend: gphoto2`, `backend: modbus`, `backend: sim`, ...). This is how acquisition
// code builds a rig without knowing which backends exist: the simulator registers "sim" from
// the sim library (sim::RegisterSimBackends()), the real ones register from rig/.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "common/yaml_reader.h"
#include "rig/axis.h"
#include "rig/camera.h"

namespace brdfrig::rig {

// `settings` is the device's YAML mapping (already past the `backend` key); a factory must read
// every key it accepts and call settings.Finish() so that unknown keys are reported with
// file:line. `base_dir` is the directory of the rig file, for relative paths in settings.
struct DeviceContext {
  std::string device_name;  // e.g. "camera", "light_arm"
  std::string base_dir;
};

using CameraFactory =
    std::function<std::unique_ptr<Camera>(const YamlNode& settings, const DeviceContext&)>;
using AxisFactory =
    std::function<std::unique_ptr<Axis>(const YamlNode& settings, const DeviceContext&)>;
using LightFactory =
    std::function<std::unique_ptr<Light>(const YamlNode& settings, const DeviceContext&)>;

void RegisterCameraBackend(const std::string& backend, CameraFactory factory);
void RegisterAxisBackend(const std::string& backend, AxisFactory factory);
void RegisterLightBackend(const std::string& backend, LightFactory factory);

// Throw a FileError at `settings` naming the known backends when `backend` is not registered.
std::unique_ptr<Camera> CreateCamera(const std::string& backend, const YamlNode& settings,
                                     const DeviceContext& context);
std::unique_ptr<Axis> CreateAxis(const std::string& backend, const YamlNode& settings,
                                 const DeviceContext& context);
std::unique_ptr<Light> CreateLight(const std::string& backend, const YamlNode& settings,
                                   const DeviceContext& context);

}  // namespace brdfrig::rig
