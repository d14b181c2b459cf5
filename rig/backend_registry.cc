#include "rig/backend_registry.h"

#include <map>
#include <mutex>

namespace brdfrig::rig {
namespace {

template <typename Factory>
struct Registry {
  std::mutex mutex;
  std::map<std::string, Factory> factories;

  void Add(const std::string& backend, Factory factory) {
    std::lock_guard lock(mutex);
    factories[backend] = std::move(factory);
  }

  Factory Find(const std::string& kind, const std::string& backend, const YamlNode& settings) {
    std::lock_guard lock(mutex);
    const auto it = factories.find(backend);
    if (it != factories.end()) return it->second;
    std::string known;
    for (const auto& entry : factories) known += (known.empty() ? "" : ", ") + entry.first;
    settings.Fail("unknown " + kind + " backend '" + backend +
                  "' (available: " + (known.empty() ? "none registered" : known) + ")");
  }
};

Registry<CameraFactory>& Cameras() {
  static Registry<CameraFactory> registry;
  return registry;
}
Registry<AxisFactory>& Axes() {
  static Registry<AxisFactory> registry;
  return registry;
}
Registry<LightFactory>& Lights() {
  static Registry<LightFactory> registry;
  return registry;
}

}  // namespace

void RegisterCameraBackend(const std::string& backend, CameraFactory factory) {
  Cameras().Add(backend, std::move(factory));
}
void RegisterAxisBackend(const std::string& backend, AxisFactory factory) {
  Axes().Add(backend, std::move(factory));
}
void RegisterLightBackend(const std::string& backend, LightFactory factory) {
  Lights().Add(backend, std::move(factory));
}

std::unique_ptr<Camera> CreateCamera(const std::string& backend, const YamlNode& settings,
                                     const DeviceContext& context) {
  return Cameras().Find("camera", backend, settings)(settings, context);
}
std::unique_ptr<Axis> CreateAxis(const std::string& backend, const YamlNode& settings,
                                 const DeviceContext& context) {
  return Axes().Find("axis", backend, settings)(settings, context);
}
std::unique_ptr<Light> CreateLight(const std::string& backend, const YamlNode& settings,
                                   const DeviceContext& context) {
  return Lights().Find("light", backend, settings)(settings, context);
}

}  // namespace brdfrig::rig
