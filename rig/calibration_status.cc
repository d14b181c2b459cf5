#include "rig/calibration_status.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "common/json_parse.h"
#include "common/utc_time.h"
#include "geometry/lens_calibration_file.h"
#include "geometry/light_calibration_file.h"
#include "geometry/white_reference_file.h"
#include "rig/rig_file.h"

namespace brdfrig::rig {
namespace {

CalibrationState Lens(const std::filesystem::path& file) {
  const geometry::LensCalibration c = geometry::ReadLensCalibration(file);
  return {"lens", file, c.created,
          Printf("reprojection RMS %.3f px, %.0f corners", c.rms_px, c.corners) +
              Printf(", frame coverage %.0f %%", 100 * c.coverage)};
}

CalibrationState White(const std::filesystem::path& file) {
  const geometry::WhiteReference r = geometry::ReadWhiteReference(file);
  return {"white reference", file, r.created,
          Printf("paper albedo %.4f, tile spread %.2f %%", r.paper_albedo, 100 * r.tile_spread)};
}

CalibrationState LightState(const std::filesystem::path& file) {
  const geometry::LightCalibration c = geometry::ReadLightCalibration(file);
  return {"light", file, c.created,
          Printf("RMS miss %.2f mm over %zu photos, %.1f mm from the nominal light",
                 1e3 * c.rms_miss_m, c.photos.size(), 1e3 * c.nominal_offset_m)};
}

// The gain map's record is the JSON `rig calibrate flat` writes beside it (FILE.json).
CalibrationState Flat(const std::filesystem::path& file) {
  CalibrationState state{"flat field", file, "", ""};
  const std::filesystem::path record = file.string() + ".json";
  std::error_code error;
  if (!std::filesystem::exists(record, error)) {
    state.figure = "no record beside the map (" + record.filename().string() + ")";
    return state;
  }
  const nlohmann::json j = ParseJson(ReadFileToString(record), record.string());
  state.created = j.value("created", "");
  if (j.contains("fit_rms") && j["fit_rms"].is_number()) {
    state.figure = Printf("fit RMS %.2f %%", 100 * j["fit_rms"].get<double>());
  }
  if (j.contains("min_gain") && j["min_gain"].is_number() && j.contains("max_gain") &&
      j["max_gain"].is_number()) {
    state.figure +=
        (state.figure.empty() ? "" : ", ") +
        Printf("gain %.3f to %.3f", j["min_gain"].get<double>(), j["max_gain"].get<double>());
  }
  return state;
}

}  // namespace

bool CalibrationStatus::Current() const {
  for (const CalibrationState& c : calibrations) {
    if (c.file.empty() || c.stale) return false;
  }
  return true;
}

std::string CalibrationStatus::ToString() const {
  std::string out =
      "rig " + rig_file.string() + ": last changed " +
      (rig_changed.empty() ? "(not said: add `changed: DATE` to rig.yaml)" : rig_changed) + "\n";
  for (const CalibrationState& c : calibrations) {
    char name[24];
    std::snprintf(name, sizeof name, "  %-16s ", c.name.c_str());
    out += name;
    if (c.file.empty()) {
      out += "NOMINAL  the rig file's values (no `calibration:` entry)\n";
      continue;
    }
    out += c.stale ? "STALE    " : "ok       ";
    out += c.file.string() + ", made " + (c.created.empty() ? "(unknown)" : c.created);
    if (!c.figure.empty()) out += "; " + c.figure;
    if (c.stale) out += c.created.empty() ? " (age unknown)" : " (before the rig's last change)";
    out += "\n";
  }
  if (!Current()) {
    out +=
        "recalibrate what is NOMINAL or STALE (`brdfrig rig calibrate lens|flat|white|light`, "
        "docs/calibration.md)\n";
  }
  return out;
}

CalibrationStatus ReadCalibrationStatus(const std::filesystem::path& rig_file) {
  const geometry::RigDescription rig = ReadRigDescription(rig_file);
  CalibrationStatus status;
  status.rig_file = rig_file;
  status.rig_changed = rig.changed;
  const geometry::RigCalibrationFiles& files = rig.calibration;
  status.calibrations = {
      files.lens.empty() ? CalibrationState{"lens"} : Lens(files.lens),
      files.flat.empty() ? CalibrationState{"flat field"} : Flat(files.flat),
      files.white.empty() ? CalibrationState{"white reference"} : White(files.white),
      files.light.empty() ? CalibrationState{"light"} : LightState(files.light)};
  const auto changed = ParseUtcIso8601(rig.changed);
  for (CalibrationState& c : status.calibrations) {
    if (c.file.empty() || !changed) continue;
    const auto created = ParseUtcIso8601(c.created);
    c.stale = !created || *created < *changed;
  }
  return status;
}

}  // namespace brdfrig::rig
