// Loads a material from a file by its kind: a brdfrig model (material.json), a measured nbrdf fit
// (.json with "format": "nbrdf-mlp") or a MERL table (.binary). Throws FileError naming the file
// for anything else.
#pragma once

#include <filesystem>
#include <memory>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

std::shared_ptr<const Brdf> LoadBrdfFile(const std::filesystem::path& path);

}  // namespace brdfrig::brdf
