// Loads a material from a file by its kind: a brdfrig model (material.json, any kind of the
// model ladder), a measured nbrdf fit (.json with "format": "nbrdf-mlp") or a MERL table
// (.binary). Throws FileError naming the file for anything else.
#pragma once

#include <filesystem>
#include <memory>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

std::shared_ptr<const Brdf> LoadBrdfFile(const std::filesystem::path& path);

// `brdfrig export`: the material sampled at the centre of every MERL bin, written as a MERL
// .binary (`output` must end in .binary), so tools that read MERL tables read any model.
void ExportMerlFile(const std::filesystem::path& material, const std::filesystem::path& output);

}  // namespace brdfrig::brdf
