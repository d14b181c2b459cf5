#include "rig/rig_file.h"

#include "common/error.h"
#include "common/utc_time.h"
#include "geometry/rig_calibration.h"
#include "rig/backend_registry.h"

namespace brdfrig::rig {
namespace {

std::filesystem::path Resolve(const std::filesystem::path& base, const std::string& path) {
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : base / p;
}

std::string BackendOf(const YamlNode& device) {
  if (!device.IsMap()) device.Fail("expected a mapping with a `backend` key");
  return device.Required("backend").AsString();
}

}  // namespace

geometry::RigDescription ReadRigDescription(const std::filesystem::path& rig_file) {
  const YamlNode root = LoadYamlFile(rig_file.string());
  const std::filesystem::path base = rig_file.parent_path();
  geometry::RigDescription description;
  description.file = rig_file;
  description.source_files.push_back(rig_file);

  const YamlNode geometry = root.Required("geometry");
  if (geometry.IsScalar()) {
    const std::filesystem::path geometry_file = Resolve(base, geometry.AsString());
    // The error_code form: a name the file system cannot even look up (a component over 255
    // bytes) is this file's error, not an exception from <filesystem> (found by fuzz_rig_yaml).
    std::error_code error;
    if (!std::filesystem::exists(geometry_file, error)) {
      geometry.Fail("geometry file not found: " + geometry_file.string() +
                    (error ? " (" + error.message() + ")" : ""));
    }
    // A scene file (or any file) whose `rig:` section is the geometry; its other sections are
    // the simulator's business, so only `rig:` is read here.
    description.geometry =
        geometry::ParseRigGeometry(LoadYamlFile(geometry_file.string()).Required("rig"));
    description.source_files.push_back(geometry_file);
  } else {
    description.geometry = geometry::ParseRigGeometry(geometry);
  }

  const YamlNode camera = root.Required("camera");
  BackendOf(camera);
  if (const auto calibration = root.Optional("calibration")) {
    // Measured values replace the nominal ones, never silently: each file must be there and of
    // this camera (geometry/rig_calibration.h refuses another one).
    geometry::RigCalibrationFiles& files = description.calibration;
    for (const geometry::CalibrationKind& kind : geometry::kCalibrationKinds) {
      if (const auto entry = calibration->Optional(kind.key)) {
        std::filesystem::path& file = files.*kind.file;
        file = Resolve(base, entry->AsString());
        std::error_code error;
        if (!std::filesystem::is_regular_file(file, error)) {
          entry->Fail(std::string(kind.key) + " calibration not found: " + file.string());
        }
      }
    }
    try {
      geometry::ApplyRigCalibration(files, camera.Get("model", std::string()),
                                    &description.geometry);
    } catch (const Error& e) {
      calibration->Fail(e.what());
    }
    calibration->Finish();
  }
  if (const auto axes = root.Optional("axes")) {
    if (!axes->IsMap()) axes->Fail("expected a mapping from axis name to its device settings");
    for (const std::string& name : axes->Keys()) {
      const YamlNode axis = axes->Required(name);
      BackendOf(axis);
      if (description.geometry.FindAxis(name) == nullptr) {
        axis.Fail("axis `" + name + "` is not in the rig geometry");
      }
    }
  }
  if (const auto light = root.Optional("light")) BackendOf(*light);
  if (const auto changed = root.Optional("changed")) {
    description.changed = changed->AsString();
    if (!ParseUtcIso8601(description.changed)) {
      changed->Fail("expected a date, 2026-12-02, or a UTC time, 2026-12-02T10:00:00Z");
    }
  }
  root.Finish();
  return description;
}

Rig OpenRig(const std::filesystem::path& rig_file) {
  ReadRigDescription(rig_file);  // configuration errors (file:line) before the lock's
  return OpenRig(rig_file, RigLock::Acquire(rig_file));
}

Rig OpenRig(const std::filesystem::path& rig_file, RigLock held) {
  Rig rig;
  rig.lock = std::move(held);
  rig.description = ReadRigDescription(rig_file);
  const YamlNode root = LoadYamlFile(rig_file.string());
  const std::string base = rig_file.parent_path().string();
  // BackendOf marks `backend` as read, so a factory's Finish() sees only its own keys.
  const YamlNode camera = root.Required("camera");
  rig.camera = CreateCamera(BackendOf(camera), camera, {"camera", base});
  if (const auto axes = root.Optional("axes")) {
    for (const std::string& name : axes->Keys()) {
      const YamlNode axis = axes->Required(name);
      rig.axes[name] = CreateAxis(BackendOf(axis), axis, {name, base});
    }
  }
  if (const auto light = root.Optional("light")) {
    rig.light = CreateLight(BackendOf(*light), *light, {"light", base});
  }
  return rig;
}

std::map<std::string, std::unique_ptr<Axis>> OpenRigAxes(const std::filesystem::path& rig_file) {
  ReadRigDescription(rig_file);
  const YamlNode root = LoadYamlFile(rig_file.string());
  const std::string base = rig_file.parent_path().string();
  std::map<std::string, std::unique_ptr<Axis>> axes;
  if (const auto section = root.Optional("axes")) {
    for (const std::string& name : section->Keys()) {
      const YamlNode axis = section->Required(name);
      axes[name] = CreateAxis(BackendOf(axis), axis, {name, base});
    }
  }
  return axes;
}

}  // namespace brdfrig::rig
