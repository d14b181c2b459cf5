#include "brdf/nbrdf_library.h"

#include <algorithm>
#include <sstream>

#include "common/atomic_file.h"

#include "common/error.h"

namespace brdfrig::brdf {

std::filesystem::path NbrdfDirectory() {
  return std::filesystem::path(BRDFRIG_SOURCE_DIR) / "data" / "materials" / "nbrdf";
}

std::vector<std::string> NbrdfMaterialNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(NbrdfDirectory(), ec)) {
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> NbrdfStudyMaterialNames() {
  std::istringstream in(ReadFileToString(NbrdfDirectory() / "study_set.txt"));
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    (void)NbrdfMaterialPath(line);  // a listed name must be a shipped material
    names.push_back(line);
  }
  return names;
}

std::filesystem::path NbrdfMaterialPath(const std::string& name) {
  const std::vector<std::string> names = NbrdfMaterialNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw Error("unknown nbrdf material '" + name + "' (known, in " + NbrdfDirectory().string() +
                ": " + (known.empty() ? "none" : known) + ")");
  }
  return NbrdfDirectory() / (name + ".json");
}

NeuralBrdf ReadNbrdfMaterial(const std::string& name) {
  return NeuralBrdf::Read(NbrdfMaterialPath(name));
}

}  // namespace brdfrig::brdf
