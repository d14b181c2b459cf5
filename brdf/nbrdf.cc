#include "brdf/nbrdf.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "brdf/json_reader.h"
#include "brdf/orthonormal_frame.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::brdf {
namespace {

using nlohmann::json;

constexpr const char* kNbrdfFormat = "nbrdf-mlp";
constexpr int kNbrdfVersion = 1;

using Reader = JsonReader;

// A vector of exactly `size` finite numbers.
template <std::size_t N>
void Vector(const JsonReader& r, const json& value, const std::string& path,
            std::array<double, N>* out) {
  if (!value.is_array() || value.size() != N) {
    r.Fail(path, "expected an array of " + std::to_string(N) + " numbers");
  }
  for (std::size_t i = 0; i < N; ++i) {
    (*out)[i] = r.Number(value[i], path + "[" + std::to_string(i) + "]");
  }
}

// A rows × cols matrix as an array of rows.
template <std::size_t R, std::size_t C>
void Matrix(const JsonReader& r, const json& value, const std::string& path,
            std::array<std::array<double, C>, R>* out) {
  if (!value.is_array() || value.size() != R) {
    r.Fail(path, "expected " + std::to_string(R) + " rows of " + std::to_string(C) + " numbers");
  }
  for (std::size_t i = 0; i < R; ++i)
    Vector(r, value[i], path + "[" + std::to_string(i) + "]", &(*out)[i]);
}

// One layer's weights, bias and activation, checked against the shapes the network must have.
template <std::size_t In, std::size_t Out>
void ParseLayer(const Reader& r, const json& layers, int index, const char* activation,
                std::array<std::array<double, Out>, In>* weights, std::array<double, Out>* bias) {
  const std::string path = "layers[" + std::to_string(index) + "]";
  const json& layer = layers[index];
  Matrix(r, r.Field(layer, path, "weights"), Reader::Join(path, "weights"), weights);
  Vector(r, r.Field(layer, path, "bias"), Reader::Join(path, "bias"), bias);
  const std::string got = r.String(layer, path, "activation");
  if (got != activation) {
    r.Fail(Reader::Join(path, "activation"),
           std::string("expected \"") + activation + "\", got \"" + got + "\"");
  }
}

}  // namespace

NeuralBrdf NeuralBrdf::Parse(const std::string& json_text, const std::string& source_name) {
  const Reader r(source_name);
  const json doc = ParseJson(json_text, source_name);
  const json& format = r.Field(doc, "", "format");
  if (format != kNbrdfFormat) {
    r.Fail("format", std::string("expected \"") + kNbrdfFormat + "\", got " + format.dump());
  }
  const json& version = r.Field(doc, "", "version");
  if (version != kNbrdfVersion) {
    r.Fail("version", "this brdfrig reads version " + std::to_string(kNbrdfVersion) + ", got " +
                          version.dump());
  }
  NeuralBrdf out;
  out.name_ = r.String(doc, "", "name");
  out.database_ = doc.contains("database") ? r.String(doc, "", "database") : "";
  const json& layers = r.Field(doc, "", "layers");
  if (!layers.is_array() || layers.size() != 3) {
    r.Fail("layers", "expected 3 layers (6→21, 21→21, 21→3)");
  }
  ParseLayer(r, layers, 0, "relu", &out.w1_, &out.b1_);
  ParseLayer(r, layers, 1, "relu", &out.w2_, &out.b2_);
  ParseLayer(r, layers, 2, "exp_minus_one", &out.w3_, &out.b3_);
  return out;
}

NeuralBrdf NeuralBrdf::Read(const std::filesystem::path& path) {
  return Parse(ReadFileToString(path), path.string());
}

Rgb NeuralBrdf::Eval(const Vec3& l, const Vec3& v, const Vec3& n) const {
  Vec3 t, b;
  OrthonormalFrame(n, &t, &b);
  return EvalLocal(Vec3(l.dot(t), l.dot(b), l.dot(n)), Vec3(v.dot(t), v.dot(b), v.dot(n)));
}

Rgb NeuralBrdf::EvalLocal(const Vec3& l, const Vec3& v) const {
  if (l.z() <= 0 || v.z() <= 0) return Rgb::Zero();
  const Vec3 h = (l + v).normalized();
  // θh and φh without trigonometric calls: cos θh = h.z, sin θh = |h.xy|, and (cos φh, sin φh)
  // = h.xy / |h.xy| (φh = 0 where h = n, as atan2(0, 0) gives).
  const double sin_h = std::hypot(h.x(), h.y());
  const double cos_h = h.z();
  double cos_p = 1, sin_p = 0;
  if (sin_h > 0) {
    cos_p = h.x() / sin_h;
    sin_p = h.y() / sin_h;
  }
  // d = R_y(−θh) · R_z(−φh) · l.
  const double x1 = cos_p * l.x() + sin_p * l.y();
  const double y1 = -sin_p * l.x() + cos_p * l.y();
  const Vec3 d = Vec3(cos_h * x1 - sin_h * l.z(), y1, sin_h * x1 + cos_h * l.z()).normalized();

  const std::array<double, kInputs> x = {sin_h, 0.0, cos_h, d.x(), d.y(), d.z()};
  std::array<double, kHidden> a1 = b1_;
  for (int i = 0; i < kInputs; ++i) {
    for (int j = 0; j < kHidden; ++j) a1[j] += x[i] * w1_[i][j];
  }
  for (double& a : a1) a = std::max(a, 0.0);
  std::array<double, kHidden> a2 = b2_;
  for (int i = 0; i < kHidden; ++i) {
    for (int j = 0; j < kHidden; ++j) a2[j] += a1[i] * w2_[i][j];
  }
  for (double& a : a2) a = std::max(a, 0.0);
  std::array<double, kOutputs> y = b3_;
  for (int i = 0; i < kHidden; ++i) {
    for (int j = 0; j < kOutputs; ++j) y[j] += a2[i] * w3_[i][j];
  }
  return Rgb(std::max(std::expm1(y[0]), 0.0), std::max(std::expm1(y[1]), 0.0),
             std::max(std::expm1(y[2]), 0.0));
}

}  // namespace brdfrig::brdf
