#include "brdf/brdf_file.h"

#include "brdf/material_file.h"
#include "brdf/merl.h"
#include "common/error.h"

namespace brdfrig::brdf {

std::shared_ptr<const Brdf> LoadBrdfFile(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return ReadMaterialFile(path).Model();
  if (ext == ".binary") return std::make_shared<MerlTable>(MerlTable::Read(path));
  throw FileError(path.string(), "unknown material file type '" + ext +
                                     "' (expected material .json or MERL .binary)");
}

void ExportMerlFile(const std::filesystem::path& material, const std::filesystem::path& output) {
  if (output.extension() != ".binary") {
    throw FileError(output.string(), "a MERL table's file name must end in .binary");
  }
  MerlTable::Tabulate(*LoadBrdfFile(material)).Write(output);
}

}  // namespace brdfrig::brdf
