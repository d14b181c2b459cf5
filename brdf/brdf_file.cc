#include "brdf/brdf_file.h"

#include <nlohmann/json.hpp>

#include "brdf/material_file.h"
#include "brdf/merl.h"
#include "brdf/nbrdf.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::brdf {

std::shared_ptr<const Brdf> LoadBrdfFile(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") {
    // Both brdfrig models and measured nbrdf fits are JSON; the "format" field tells them apart.
    const std::string text = ReadFileToString(path);
    const nlohmann::json doc = ParseJson(text, path.string());
    if (doc.is_object() && doc.contains("format") && doc["format"] == "nbrdf-mlp") {
      return std::make_shared<NeuralBrdf>(NeuralBrdf::Parse(text, path.string()));
    }
    return ParseMaterial(text, path.string()).Model();
  }
  if (ext == ".binary") return std::make_shared<MerlTable>(MerlTable::Read(path));
  throw FileError(path.string(), "unknown material file type '" + ext +
                                     "' (expected material .json, nbrdf .json or MERL .binary)");
}

void ExportMerlFile(const std::filesystem::path& material, const std::filesystem::path& output) {
  if (output.extension() != ".binary") {
    throw FileError(
        output.string(),
        "a MERL table's file name must end in .binary (a glTF file's in .glb or .gltf)");
  }
  const MerlTable table = MerlTable::Tabulate(*LoadBrdfFile(material));
  // A model finite in double can overflow the table's scale (A1 = 1e308 times 1500).
  if (const std::size_t bad = table.NonFiniteCount(); bad > 0) {
    throw FileError(material.string(), "its MERL table would hold " + std::to_string(bad) +
                                           " infinite or NaN values (the model's values are too "
                                           "large); nothing written to " +
                                           output.string());
  }
  table.Write(output);
}

}  // namespace brdfrig::brdf
