// GLSL sources by file name. Loaded from the source tree's shaders/ when it is there (edit and
// re-run without rebuilding), else from the copies embedded at build time.
#pragma once

#include <map>
#include <string>

namespace brdfrig::render {

const std::map<std::string, std::string>& EmbeddedShaders();

// Throws brdfrig::Error when `name` is neither on disk nor embedded.
std::string LoadShaderSource(const std::string& name);

}  // namespace brdfrig::render
