#include "rig/rig_tools.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "rig/backend_registry.h"
#include "rig/gphoto2_camera.h"
#include "rig/modbus_axis.h"
#include "rig/modbus_light.h"
#include "rig/rig_file.h"
#include "rig/shutter_speed.h"

namespace brdfrig::rig {
namespace {

std::string ExposureLabel(double seconds) {
  if (seconds < 0.5) return "1/" + Printf("%.0f", 1 / seconds) + " s";
  return Printf("%g", seconds) + " s";
}

DeviceContext Context(const std::filesystem::path& rig_file, const std::string& name) {
  return {name, rig_file.parent_path().string()};
}

std::string CameraDetail(Camera& camera, const std::string& backend) {
  const CameraInfo info = camera.Info();
  std::string detail = backend + " " + info.model + " at " + info.port;
  if (!info.serial.empty()) detail += ", serial " + info.serial;
  if (!info.firmware.empty()) detail += ", firmware " + info.firmware;
  if (info.shutter_speeds.empty()) {
    detail += ", no shutter speeds offered (mode dial on M?)";
  } else {
    detail += ", " + std::to_string(info.shutter_speeds.size()) + " shutter speeds (" +
              ExposureLabel(info.shutter_speeds.front()) + " .. " +
              ExposureLabel(info.shutter_speeds.back()) + ")";
  }
  if (auto* gphoto2 = dynamic_cast<Gphoto2Camera*>(&camera)) {
    std::string settings;
    for (const auto& [name, value] : gphoto2->CurrentSettings()) {
      settings += (settings.empty() ? "" : ", ") + name + " " + value;
    }
    if (!settings.empty()) detail += "; now: " + settings;
  }
  return detail;
}

void CheckAxis(Axis& axis, const std::string& backend, DeviceCheck& check) {
  const auto* modbus = dynamic_cast<const ModbusAxis*>(&axis);
  std::string where = modbus ? modbus->Describe() : backend;
  const AxisStatus status = axis.Status();
  const std::string position = Printf("%.3f deg", Degrees(status.position));
  switch (status.state) {
    case AxisState::kReady:
      check.ok = true;
      check.detail = where + ": ready at " + position;
      if (modbus) check.detail += " (" + modbus->Settings() + ")";
      break;
    case AxisState::kMoving:
      check.ok = true;
      check.detail = where + ": moving, at " + position;
      break;
    case AxisState::kAlarm:
      check.detail = where + ": ALARM " + Hex(status.alarm_code) + " at " + position +
                     " (clear the cause, then reset the alarm at the drive)";
      break;
    case AxisState::kDisconnected:
      check.detail = where + ": not answering: " + status.message;
      break;
  }
}

// Opens one axis named in rig.yaml.
std::unique_ptr<Axis> OpenAxis(const std::filesystem::path& rig_file, const std::string& name) {
  ReadRigDescription(rig_file);  // whole-file validation first (file:line errors)
  const YamlNode root = LoadYamlFile(rig_file.string());
  const auto axes = root.Optional("axes");
  if (!axes || !axes->Has(name)) {
    std::string known;
    if (axes) {
      for (const std::string& k : axes->Keys()) known += (known.empty() ? "" : ", ") + k;
    }
    throw Error(rig_file.string() + ": no axis '" + name +
                "' under `axes` (configured: " + (known.empty() ? "none" : known) + ")");
  }
  const YamlNode settings = axes->Required(name);
  return CreateAxis(settings.Required("backend").AsString(), settings, Context(rig_file, name));
}

}  // namespace

bool RigCheckReport::ok() const {
  for (const DeviceCheck& d : devices) {
    if (!d.ok) return false;
  }
  return !devices.empty();
}

std::string RigCheckReport::ToString() const {
  std::ostringstream out;
  out << "rig " << rig_file.string() << "\n";
  std::size_t width = 0;
  int good = 0;
  for (const DeviceCheck& d : devices) width = std::max(width, d.name.size());
  for (const DeviceCheck& d : devices) {
    out << "  " << d.name << std::string(width - d.name.size() + 2, ' ')
        << (d.ok ? "OK    " : "FAIL  ") << d.detail << "\n";
    good += d.ok ? 1 : 0;
  }
  out << "rig check: " << good << " of " << devices.size() << " devices OK"
      << (ok() ? "" : " -- fix the FAIL lines above before capturing");
  return out.str();
}

RigCheckReport CheckRig(const std::filesystem::path& rig_file) {
  RigCheckReport report;
  report.rig_file = rig_file;
  const geometry::RigDescription description = ReadRigDescription(rig_file);
  const RigLock owner = RigLock::Acquire(rig_file);  // a running capture keeps its devices
  const YamlNode root = LoadYamlFile(rig_file.string());

  auto check = [&](const std::string& name, const YamlNode& settings, auto open_and_describe) {
    DeviceCheck device;
    device.name = name;
    device.backend = settings.Required("backend").AsString();
    try {
      open_and_describe(device);
    } catch (const FileError&) {
      throw;  // configuration errors stop the check: they name file:line
    } catch (const Error& e) {
      device.ok = false;
      device.detail = device.backend + ": " + e.what();
    }
    report.devices.push_back(device);
  };

  const YamlNode camera = root.Required("camera");
  check("camera", camera, [&](DeviceCheck& d) {
    const auto opened = CreateCamera(d.backend, camera, Context(rig_file, "camera"));
    d.detail = CameraDetail(*opened, d.backend);
    d.ok = true;
  });
  if (const auto axes = root.Optional("axes")) {
    for (const std::string& name : axes->Keys()) {
      const YamlNode settings = axes->Required(name);
      check(name, settings, [&](DeviceCheck& d) {
        const auto axis = CreateAxis(d.backend, settings, Context(rig_file, name));
        CheckAxis(*axis, d.backend, d);
      });
    }
  }
  for (const geometry::RotationAxis& axis : description.geometry.axes) {
    if (!root.Optional("axes") || !root.Optional("axes")->Has(axis.name)) {
      report.devices.push_back(
          {axis.name, "-", true, "in the geometry but not motorized (fixed at 0)"});
    }
  }
  if (const auto light = root.Optional("light")) {
    check("light", *light, [&](DeviceCheck& d) {
      const auto opened = CreateLight(d.backend, *light, Context(rig_file, "light"));
      if (auto* modbus = dynamic_cast<ModbusLight*>(opened.get())) {
        d.detail = modbus->Describe() + (modbus->IsOn() ? ": on" : ": off");
      } else {
        d.detail = d.backend + ": opened";
      }
      d.ok = true;
    });
  }
  return report;
}

MoveReport MoveAxis(const std::filesystem::path& rig_file, const std::string& axis,
                    double angle_deg) {
  if (!std::isfinite(angle_deg)) throw OptionsError("rig move: the angle must be a finite number");
  const RigLock owner = RigLock::Acquire(rig_file);  // never move an axis a capture is using
  return OpenAxis(rig_file, axis)->MoveTo(Radians(angle_deg));
}

std::string ShootReport::ToString() const {
  std::string text = "exposure " + ExposureLabel(exposure_s) + ":";
  for (const auto& f : files) text += " " + f.string();
  return text;
}

ShootReport Shoot(const std::filesystem::path& rig_file, const std::string& exposure,
                  const std::filesystem::path& output) {
  const double seconds = ParseExposureText(exposure);
  ReadRigDescription(rig_file);
  const RigLock owner = RigLock::Acquire(rig_file);
  const YamlNode root = LoadYamlFile(rig_file.string());
  const YamlNode settings = root.Required("camera");
  const auto camera =
      CreateCamera(settings.Required("backend").AsString(), settings, Context(rig_file, "camera"));
  ShootReport report;
  report.exposure_s = camera->SetExposure(seconds);
  const std::vector<Frame> frames = camera->Capture();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    std::filesystem::path path = output;
    if (i > 0) {
      // RAW+JPEG: the other file keeps its own extension next to the requested name.
      path.replace_extension(std::filesystem::path(frames[i].file_name).extension());
      if (path == output) path = output.string() + "." + std::to_string(i);
    }
    WriteFileAtomically(path, frames[i].bytes);
    report.files.push_back(path);
  }
  return report;
}

}  // namespace brdfrig::rig
