#include "geometry/lens_calibration_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::geometry {
namespace {

constexpr const char* kLensCalibrationFormat = "brdfrig-lens-calibration";

nlohmann::json IntrinsicsJson(const Intrinsics& k, bool with_size) {
  nlohmann::json j = {{"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx},
                      {"cy", k.cy}, {"k1", k.k1}, {"k2", k.k2}};
  if (with_size) {
    j["width"] = k.width;
    j["height"] = k.height;
  }
  return j;
}

double Finite(const nlohmann::json& j, const char* key, const std::string& where) {
  const double v = j.at(key).get<double>();
  if (!std::isfinite(v)) throw Error(where + "." + key + " is not a finite number");
  return v;
}

// An integer field read without nlohmann's unchecked cast from a floating-point number (1e300
// would overflow an int).
int Integer(const nlohmann::json& j, const char* key, const std::string& where) {
  const double v = j.at(key).get<double>();
  if (!(v >= -1e9 && v <= 1e9) || v != std::floor(v)) {
    throw Error(where + "." + key + " is not an integer of reasonable size");
  }
  return static_cast<int>(v);
}

Intrinsics ReadIntrinsics(const nlohmann::json& j, const std::string& where, bool with_size) {
  Intrinsics k;
  if (with_size) {
    k.width = Integer(j, "width", where);
    k.height = Integer(j, "height", where);
  }
  k.fx = Finite(j, "fx", where);
  k.fy = Finite(j, "fy", where);
  k.cx = Finite(j, "cx", where);
  k.cy = Finite(j, "cy", where);
  k.k1 = Finite(j, "k1", where);
  k.k2 = Finite(j, "k2", where);
  return k;
}

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

nlohmann::json LensCalibration::ToJson() const {
  nlohmann::json photo_errors = nlohmann::json::array();
  for (const PhotoCalibrationError& p : photos) {
    photo_errors.push_back({{"photo", p.photo},
                            {"corners", p.corners},
                            {"rms_px", p.rms_px},
                            {"edge_width_px", p.edge_width_px}});
  }
  return {{"format", kLensCalibrationFormat},
          {"version", 1},
          {"created", created},
          {"software", software},
          {"camera", {{"model", camera_model}, {"serial", camera_serial}}},
          {"board", board},
          {"settings", settings},
          {"intrinsics", IntrinsicsJson(intrinsics, true)},
          {"uncertainty", IntrinsicsJson(uncertainty, false)},
          {"errors",
           {{"rms_px", rms_px},
            {"coverage", coverage},
            {"corners", corners},
            {"photos", photo_errors}}}};
}

void WriteLensCalibration(const std::filesystem::path& path, const LensCalibration& calibration) {
  WriteFileAtomically(path, calibration.ToJson().dump(2) + "\n");
}

LensCalibration ReadLensCalibration(const std::filesystem::path& path) {
  const nlohmann::json j = ParseJson(ReadFileToString(path), path.string());
  LensCalibration c;
  try {
    if (j.at("format").get<std::string>() != kLensCalibrationFormat) {
      throw Error(std::string("not a lens calibration (format is not \"") + kLensCalibrationFormat +
                  "\")");
    }
    if (Integer(j, "version", "") != 1) throw Error("version: only version 1 is known");
    c.created = j.at("created").get<std::string>();
    c.software = j.value("software", "");
    c.camera_model = j.at("camera").value("model", "");
    c.camera_serial = j.at("camera").value("serial", "");
    c.board = j.at("board");
    c.settings = j.value("settings", nlohmann::json::object());
    c.intrinsics = ReadIntrinsics(j.at("intrinsics"), "intrinsics", true);
    c.uncertainty = ReadIntrinsics(j.at("uncertainty"), "uncertainty", false);
    const nlohmann::json& errors = j.at("errors");
    c.rms_px = Finite(errors, "rms_px", "errors");
    c.coverage = Finite(errors, "coverage", "errors");
    c.corners = Integer(errors, "corners", "errors");
    for (const nlohmann::json& p : errors.at("photos")) {
      c.photos.push_back(
          {p.at("photo").get<std::string>(), Integer(p, "corners", "errors.photos[]"),
           Finite(p, "rms_px", "errors.photos[]"), Finite(p, "edge_width_px", "errors.photos[]")});
    }
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path.string(), std::string("lens calibration: ") + e.what());
  } catch (const Error& e) {
    throw FileError(path.string(), std::string("lens calibration: ") + e.what());
  }
  const Intrinsics& k = c.intrinsics;
  if (k.width <= 0 || k.height <= 0 || !(k.fx > 0) || !(k.fy > 0) || k.cx < 0 || k.cx > k.width ||
      k.cy < 0 || k.cy > k.height) {
    throw FileError(path.string(),
                    "lens calibration: intrinsics implausible (image size, focal lengths > 0, "
                    "principal point inside the image)");
  }
  return c;
}

Intrinsics ApplyLensCalibration(const LensCalibration& calibration,
                                const std::filesystem::path& source, const Intrinsics& nominal,
                                const std::string& rig_camera_model) {
  const Intrinsics& k = calibration.intrinsics;
  if (k.width != nominal.width || k.height != nominal.height) {
    throw FileError(source.string(),
                    "a calibration of another camera: it was made from " + std::to_string(k.width) +
                        "x" + std::to_string(k.height) + " photos, the rig's camera takes " +
                        std::to_string(nominal.width) + "x" + std::to_string(nominal.height));
  }
  if (!calibration.camera_model.empty() && !rig_camera_model.empty() &&
      Lower(calibration.camera_model) != Lower(rig_camera_model)) {
    throw FileError(source.string(), "a calibration of another camera: it is of a '" +
                                         calibration.camera_model + "', the rig's camera is a '" +
                                         rig_camera_model + "'");
  }
  return k;
}

}  // namespace brdfrig::geometry
