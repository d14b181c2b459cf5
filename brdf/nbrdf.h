// Measured materials as small neural fits (Sztrajman et al., "Neural BRDF Representation and
// Importance Sampling", CGF 2021; files in data/materials/nbrdf/, format in its README).
//
// A fit is a 6→21→21→3 multilayer perceptron of the Rusinkiewicz half/difference angles:
//
//     x = [sin θh, 0, cos θh, d.x, d.y, d.z]      (d: the difference vector, unit)
//     a = relu(x·W1 + b1);  a = relu(a·W2 + b2);  f_rgb = max(exp(a·W3 + b3) − 1, 0)   [1/sr]
//
// Eval is called millions of times by the simulator and the metrics: the weights live in
// fixed-size arrays and an evaluation allocates nothing.
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

class NeuralBrdf : public Brdf {
 public:
  static constexpr int kInputs = 6;
  static constexpr int kHidden = 21;
  static constexpr int kOutputs = 3;

  // Parses an "nbrdf-mlp" version 1 document. Throws FileError naming `source_name` and the JSON
  // path of what is wrong (format, version, layer shapes, activations, non-finite numbers).
  static NeuralBrdf Parse(const std::string& json_text, const std::string& source_name);
  static NeuralBrdf Read(const std::filesystem::path& path);

  Rgb Eval(const Vec3& l, const Vec3& v, const Vec3& n) const override;
  // The forward pass in the local frame (z = normal); 0 when l or v is below the surface.
  Rgb EvalLocal(const Vec3& l, const Vec3& v) const;
  std::string Name() const override { return "nbrdf(" + name_ + ")"; }

  const std::string& material_name() const { return name_; }
  const std::string& database() const { return database_; }  // merl | rgl | dtu

 private:
  NeuralBrdf() = default;

  std::string name_;
  std::string database_;
  // weights[i][j]: input i to output j, as in the file (row vector times matrix).
  std::array<std::array<double, kHidden>, kInputs> w1_{};
  std::array<double, kHidden> b1_{};
  std::array<std::array<double, kHidden>, kHidden> w2_{};
  std::array<double, kHidden> b2_{};
  std::array<std::array<double, kOutputs>, kHidden> w3_{};
  std::array<double, kOutputs> b3_{};
};

}  // namespace brdfrig::brdf
