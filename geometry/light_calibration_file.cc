#include "geometry/light_calibration_file.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::geometry {
namespace {

constexpr const char* kLightCalibrationFormat = "brdfrig-light-calibration";

double Finite(const nlohmann::json& j, const char* key) {
  const double v = j.at(key).get<double>();
  if (!std::isfinite(v)) throw Error(std::string(key) + " is not a finite number");
  return v;
}

}  // namespace

void WriteLightCalibration(const std::filesystem::path& path, const LightCalibration& c) {
  nlohmann::json photos = nlohmann::json::array();
  for (const LightCalibrationPhoto& p : c.photos) {
    photos.push_back({{"photo", p.photo},
                      {"positions_deg", p.positions_deg},
                      {"highlight_px", {p.highlight_x, p.highlight_y}},
                      {"miss_m", p.miss_m}});
  }
  const Vec3& l = c.light_position;
  const nlohmann::json j = {{"format", kLightCalibrationFormat},
                            {"version", 1},
                            {"created", c.created},
                            {"software", c.software},
                            {"light_position", {l.x(), l.y(), l.z()}},
                            {"nominal_offset_m", c.nominal_offset_m},
                            {"rms_miss_m", c.rms_miss_m},
                            {"dilution", c.dilution},
                            {"photos", photos}};
  WriteFileAtomically(path, j.dump(2) + "\n");
}

LightCalibration ReadLightCalibration(const std::filesystem::path& path) {
  const nlohmann::json j = ParseJson(ReadFileToString(path), path.string());
  LightCalibration c;
  try {
    if (j.at("format").get<std::string>() != kLightCalibrationFormat) {
      throw Error(std::string("not a light calibration (format is not \"") +
                  kLightCalibrationFormat + "\")");
    }
    if (j.at("version").get<double>() != 1) throw Error("version: only version 1 is known");
    c.created = j.at("created").get<std::string>();
    c.software = j.value("software", "");
    const auto position = j.at("light_position").get<std::vector<double>>();
    if (position.size() != 3) throw Error("light_position: expected [x, y, z]");
    c.light_position = {position[0], position[1], position[2]};
    if (!c.light_position.allFinite() || !(c.light_position.z() > 0)) {
      throw Error("light_position must be finite and above the sample plane (z > 0)");
    }
    c.nominal_offset_m = Finite(j, "nominal_offset_m");
    c.rms_miss_m = Finite(j, "rms_miss_m");
    c.dilution = Finite(j, "dilution");
    for (const nlohmann::json& p : j.value("photos", nlohmann::json::array())) {
      LightCalibrationPhoto photo;
      photo.photo = p.value("photo", "");
      photo.positions_deg = p.value("positions_deg", std::map<std::string, double>{});
      const auto at = p.value("highlight_px", std::vector<double>{-1, -1});
      if (at.size() == 2) {
        photo.highlight_x = at[0];
        photo.highlight_y = at[1];
      }
      photo.miss_m = p.value("miss_m", 0.0);
      c.photos.push_back(photo);
    }
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path.string(), std::string("light calibration: ") + e.what());
  } catch (const Error& e) {
    throw FileError(path.string(), std::string("light calibration: ") + e.what());
  }
  return c;
}

}  // namespace brdfrig::geometry
