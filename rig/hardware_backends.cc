#include "rig/hardware_backends.h"

#include "rig/backend_registry.h"
#include "rig/drive_profile.h"
#include "rig/gphoto2_camera.h"
#include "rig/modbus_axis.h"
#include "rig/modbus_light.h"

namespace brdfrig::rig {
namespace {

std::unique_ptr<Axis> OpenModbusAxis(const YamlNode& settings, const DeviceContext& context) {
  const ModbusLinkOptions link = ReadModbusLinkOptions(settings);
  const ModbusAxisOptions options = ReadModbusAxisOptions(settings);
  const YamlNode profile_node = settings.Required("profile");
  DriveProfile profile;
  try {
    profile = LoadDriveProfile(profile_node.AsString(), context.base_dir);
  } catch (const FileError&) {
    throw;  // an error inside the profile file already names its own file:line
  } catch (const Error& e) {
    profile_node.Fail(e.what());
  }
  settings.Finish();
  return std::make_unique<ModbusAxis>(context.device_name, SharedModbusLink(link), profile,
                                      options);
}

std::unique_ptr<Light> OpenModbusLight(const YamlNode& settings, const DeviceContext&) {
  const ModbusLinkOptions link = ReadModbusLinkOptions(settings);
  int slave = 1;  // 0 would be a broadcast, which gets no answer
  if (const auto n = settings.Optional("slave"))
    slave = static_cast<int>(n->InRange(n->AsInt(), 1, 247));
  const YamlNode coil = settings.Required("coil");
  const int address = static_cast<int>(coil.InRange(coil.AsInt(), 0, 65535));
  settings.Finish();
  return std::make_unique<ModbusLight>(SharedModbusLink(link), slave, address);
}

std::unique_ptr<Camera> OpenGphoto2Camera(const YamlNode& settings, const DeviceContext&) {
  const Gphoto2Options options = ReadGphoto2Options(settings);
  settings.Finish();
  return std::make_unique<Gphoto2Camera>(options);
}

}  // namespace

void RegisterHardwareBackends() {
  RegisterCameraBackend("gphoto2", OpenGphoto2Camera);
  RegisterAxisBackend("modbus", OpenModbusAxis);
  RegisterLightBackend("modbus", OpenModbusLight);
}

}  // namespace brdfrig::rig
