#include "render/shader_sources.h"

#include <filesystem>

#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig::render {

std::string LoadShaderSource(const std::string& name) {
  const std::filesystem::path on_disk =
      std::filesystem::path(BRDFRIG_SOURCE_DIR) / "shaders" / name;
  if (std::filesystem::exists(on_disk)) return ReadFileToString(on_disk);
  const auto& embedded = EmbeddedShaders();
  const auto it = embedded.find(name);
  if (it == embedded.end()) throw Error("shader '" + name + "' not found");
  return it->second;
}

}  // namespace brdfrig::render
