#include "geometry/rig_calibration.h"

#include <vector>

#include "common/sha256.h"
#include "geometry/lens_calibration_file.h"
#include "geometry/rig_geometry.h"
#include "geometry/white_reference_file.h"

namespace brdfrig::geometry {
namespace {

struct Entry {
  const char* key;
  const char* name;  // for people
  const std::filesystem::path* file;
};

std::vector<Entry> Entries(const RigCalibrationFiles& f) {
  return {{"lens", "lens", &f.lens},
          {"flat", "flat field", &f.flat},
          {"white", "white reference", &f.white}};
}

}  // namespace

nlohmann::json RigCalibrationFiles::Provenance() const {
  nlohmann::json j = nlohmann::json::object();
  for (const Entry& e : Entries(*this)) {
    if (e.file->empty()) {
      j[e.key] = "nominal";
      continue;
    }
    Sha256 hash;
    hash.UpdateFile(*e.file);
    j[e.key] = {{"file", e.file->filename().string()}, {"sha256", hash.HexDigest()}};
  }
  return j;
}

std::string RigCalibrationFiles::NominalOnes() const {
  std::string names;
  for (const Entry& e : Entries(*this)) {
    if (!e.file->empty()) continue;
    names += (names.empty() ? "" : ", ") + std::string(e.name);
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
}

}  // namespace brdfrig::geometry
