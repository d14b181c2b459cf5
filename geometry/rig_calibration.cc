#include "geometry/rig_calibration.h"

#include "common/sha256.h"
#include "geometry/lens_calibration_file.h"
#include "geometry/light_calibration_file.h"
#include "geometry/rig_geometry.h"
#include "geometry/white_reference_file.h"

namespace brdfrig::geometry {
bool RigCalibrationFiles::Empty() const {
  for (const CalibrationKind& kind : kCalibrationKinds) {
    if (!(this->*kind.file).empty()) return false;
  }
  return true;
}

nlohmann::json RigCalibrationFiles::Provenance() const {
  nlohmann::json j = nlohmann::json::object();
  for (const CalibrationKind& kind : kCalibrationKinds) {
    const std::filesystem::path& file = this->*kind.file;
    if (file.empty()) {
      j[kind.key] = "nominal";
      continue;
    }
    Sha256 hash;
    hash.UpdateFile(file);
    j[kind.key] = {{"file", file.filename().string()}, {"sha256", hash.HexDigest()}};
  }
  return j;
}

std::string RigCalibrationFiles::NominalOnes() const {
  std::string names;
  for (const CalibrationKind& kind : kCalibrationKinds) {
    if (!(this->*kind.file).empty()) continue;
    names += (names.empty() ? "" : ", ") + std::string(kind.name);
  }
  return names;
}

void ApplyRigCalibration(const RigCalibrationFiles& files, const std::string& camera_model,
                         RigGeometry* geometry) {
  if (!files.lens.empty()) {
    geometry->intrinsics = ApplyLensCalibration(ReadLensCalibration(files.lens), files.lens,
                                                geometry->intrinsics, camera_model);
  }
  if (!files.white.empty()) {
    geometry->target.paper_albedo = ReadWhiteReference(files.white).paper_albedo;
  }
  if (!files.light.empty()) {
    geometry->light_position = ReadLightCalibration(files.light).light_position;
  }
}

}  // namespace brdfrig::geometry
