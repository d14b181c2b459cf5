#include "brdf/gltf_model.h"

#include <cmath>
#include <sstream>

#include "brdf/gltf_terms.h"
#include "common/error.h"
#include "common/format.h"

namespace brdfrig::brdf {
namespace {

[[noreturn]] void Invalid(const std::string& field, const std::string& rule, double got) {
  std::ostringstream msg;
  msg.precision(17);
  msg << field << " = " << got << "; " << rule;
  throw Error(msg.str());
}

void CheckRange(double x, double lo, double hi, const std::string& field) {
  if (!(x >= lo && x <= hi)) {
    std::ostringstream rule;
    rule << "must be finite and in [" << lo << ", " << hi << "]";
    Invalid(field, rule.str(), x);
  }
}

void CheckColour(const Rgb& c, double hi, const char* field) {
  static constexpr const char* kChannels[3] = {"red", "green", "blue"};
  for (int i = 0; i < 3; ++i) CheckRange(c[i], 0, hi, std::string(field) + "." + kChannels[i]);
}

}  // namespace

void GltfParams::Validate() const {
  CheckColour(base_color, 1, "base_color");
  CheckRange(metallic, 0, 1, "metallic");
  // glTF allows 0, a mirror (alpha = 0: D a delta); a measured material is never one, and
  // alpha = 1e-4 is already finer than float32 resolves near the peak.
  CheckRange(roughness, 0.01, 1, "roughness");
  CheckRange(ior, 1, 10, "ior");
  CheckRange(specular, 0, 1, "specular");
  CheckColour(specular_color, 100, "specular_color");
}

Rgb GltfParams::DielectricF0() const { return (gltf::IorF0(ior) * specular_color).min(1.0); }

GltfModel::GltfModel(GltfParams params) : params_(std::move(params)) { params_.Validate(); }

Rgb GltfModel::Eval(const Vec3& l, const Vec3& v, const Vec3& n) const {
  const double n_dot_l = n.dot(l), n_dot_v = n.dot(v);
  if (n_dot_l <= 0 || n_dot_v <= 0) return Rgb::Zero();
  const Vec3 h = (l + v).normalized();
  gltf::Params<double> p;
  for (int c = 0; c < 3; ++c) {
    p.base_color[c] = params_.base_color[c];
    p.specular_color[c] = params_.specular_color[c];
  }
  p.metallic = params_.metallic;
  p.roughness = params_.roughness;
  p.ior = params_.ior;
  p.specular = params_.specular;
  double out[3];
  gltf::Eval(p, n_dot_l, n_dot_v, std::max(n.dot(h), 0.0), v.dot(h), out);
  return Rgb(out[0], out[1], out[2]);
}

std::string GltfModel::Name() const {
  const GltfParams& p = params_;
  return "gltf(base=" + Fixed(p.base_color[0], 3) + "," + Fixed(p.base_color[1], 3) + "," +
         Fixed(p.base_color[2], 3) + " metallic=" + Fixed(p.metallic, 3) +
         " roughness=" + Fixed(p.roughness, 3) + " ior=" + Fixed(p.ior, 3) +
         " specular=" + Fixed(p.specular, 3) + ")";
}

}  // namespace brdfrig::brdf
