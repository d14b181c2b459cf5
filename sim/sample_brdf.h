// The sample's material in a scene: any brdf/ model, analytic with parameters or from a file.
//   {model: ggx | cook_torrance, diffuse: RGB, f0: RGB, alpha: a}
//   {model: ward, diffuse: RGB, specular: RGB, alpha: a}
//   {model: blinn_phong, diffuse: RGB, specular: RGB, exponent: e}
//   {model: lambert, albedo: RGB}
//   {model: slices, file: material.json}    {model: merl, file: name.binary}
//   {model: nbrdf, name: gold-metallic-paint}  (a measured material in data/materials/nbrdf/)
//   {model: nbrdf, file: fit.json}             (any nbrdf-mlp file, relative to the scene)
#pragma once

#include <filesystem>
#include <memory>

#include "brdf/brdf.h"
#include "common/yaml_reader.h"

namespace brdfrig::sim {

std::shared_ptr<const brdf::Brdf> ParseSampleBrdf(const YamlNode& node,
                                                  const std::filesystem::path& base_dir);

}  // namespace brdfrig::sim
