// The `gltf` model kind: the glTF 2.0 metal-rough BRDF exactly as the specification's
// Appendix B defines it, extended by KHR_materials_ior and KHR_materials_specular (the
// formulas: brdf/gltf_terms.h). It is what a glTF consumer renders from an exported material
// (reconstruct/gltf_export.h), so fitting and scoring it tells how much of a fit survives the
// export (docs/gltf.md).
#pragma once

#include <string>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

struct GltfParams {
  Rgb base_color = Rgb::Constant(0.8);  // pbrMetallicRoughness.baseColorFactor (linear), [0, 1]
  double metallic = 0;                  // metallicFactor, [0, 1]
  double roughness = 0.5;               // roughnessFactor, [0.01, 1]; alpha = roughness²
  double ior = 1.5;                     // KHR_materials_ior, [1, 10]
  double specular = 1;                  // KHR_materials_specular specularFactor, [0, 1]
  Rgb specular_color = Rgb::Ones();     // specularColorFactor, [0, 100] (the extension: >= 0)

  // Throws brdfrig::Error naming the field (as material.json spells it), its value and rule.
  void Validate() const;
  // The dielectric f0 before `specular`: min(((ior − 1)/(ior + 1))² · specularColor, 1).
  Rgb DielectricF0() const;
};

class GltfModel : public Brdf {
 public:
  explicit GltfModel(GltfParams params);  // validates

  Rgb Eval(const Vec3& l, const Vec3& v, const Vec3& n) const override;
  std::string Name() const override;
  const GltfParams& params() const { return params_; }

 private:
  GltfParams params_;
};

}  // namespace brdfrig::brdf
