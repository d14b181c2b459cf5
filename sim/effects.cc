#include "sim/effects.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/angles.h"
#include "common/srgb.h"
#include "sim/yaml_values.h"

namespace brdfrig::sim {
namespace {

double ReadPositive(const YamlNode& effect, const std::string& key, double fallback) {
  auto node = effect.Optional(key);
  return node ? node->Positive(node->AsDouble()) : fallback;
}

AreaLightEffect ParseAreaLight(const YamlNode& node) {
  AreaLightEffect e;
  e.radius = ReadPositive(node, "radius", e.radius);
  if (auto samples = node.Optional("samples")) {
    e.samples = static_cast<int>(samples->InRange(samples->AsInt(), 1, 4096));
  }
  return e;
}

AmbientEffect ParseAmbient(const YamlNode& node) {
  return {ReadRgb(node.Required("radiance"), 0, 1e9)};
}

RadialDistortionEffect ParseRadialDistortion(const YamlNode& node) {
  RadialDistortionEffect e;
  if (auto k1 = node.Optional("k1")) e.k1 = k1->InRange(k1->AsDouble(), -1, 1);
  if (auto k2 = node.Optional("k2")) e.k2 = k2->InRange(k2->AsDouble(), -1, 1);
  return e;
}

VignettingEffect ParseVignetting(const YamlNode& node) {
  VignettingEffect e;
  const std::string falloff = node.Get("falloff", "cos4");
  if (falloff == "cos4") {
    e.falloff = VignettingEffect::Falloff::kCos4;
  } else if (falloff == "polynomial") {
    e.falloff = VignettingEffect::Falloff::kPolynomial;
    const YamlNode a1 = node.Required("a1");
    e.a1 = a1.AsDouble();
    e.a2 = node.Get("a2", 0.0);
    // The factor must stay within [0, 1] over r in [0, 1] (a lens only loses light).
    for (int i = 0; i <= 100; ++i) {
      const double r2 = (i / 100.0) * (i / 100.0);
      const double f = 1 + e.a1 * r2 + e.a2 * r2 * r2;
      if (f < 0 || f > 1) a1.Fail("1 + a1 r² + a2 r⁴ must stay within [0, 1] for r in [0, 1]");
    }
  } else {
    node.Required("falloff").Fail("expected cos4 or polynomial, got '" + falloff + "'");
  }
  return e;
}

ShotNoiseEffect ParseShotNoise(const YamlNode& node) {
  return {ReadPositive(node, "full_well", ShotNoiseEffect{}.full_well)};
}

ReadNoiseEffect ParseReadNoise(const YamlNode& node) {
  const YamlNode sigma = node.Required("sigma");
  return {sigma.InRange(sigma.AsDouble(), 0, 1)};
}

SaturationEffect ParseSaturation(const YamlNode& node) {
  return {ReadPositive(node, "level", 1.0)};
}

QuantizationEffect ParseQuantization(const YamlNode& node) {
  const YamlNode bits = node.Required("bits");
  return {static_cast<int>(bits.InRange(bits.AsInt(), 1, 16))};
}

ResponseCurveEffect ParseResponseCurve(const YamlNode& node) {
  ResponseCurveEffect e;
  const YamlNode curve = node.Required("curve");
  const std::string name = curve.AsString();
  if (name == "srgb") {
    e.curve = ResponseCurveEffect::Curve::kSrgb;
  } else if (name == "gamma") {
    e.curve = ResponseCurveEffect::Curve::kGamma;
    const YamlNode gamma = node.Required("gamma");
    e.gamma = gamma.InRange(gamma.AsDouble(), 0.1, 10);
  } else if (name == "table") {
    e.curve = ResponseCurveEffect::Curve::kTable;
    const YamlNode values = node.Required("values");
    e.table = values.AsDoubles();
    if (e.table.size() < 2) values.Fail("expected at least 2 values");
    for (std::size_t i = 0; i < e.table.size(); ++i) {
      if (e.table[i] < 0 || e.table[i] > 1) values.Fail("values must be in [0, 1]");
      if (i > 0 && e.table[i] < e.table[i - 1]) values.Fail("values must be non-decreasing");
    }
  } else {
    curve.Fail("expected srgb, gamma or table, got '" + name + "'");
  }
  return e;
}

MechanicalErrorEffect ParseMechanicalError(const YamlNode& node) {
  MechanicalErrorEffect e;
  if (auto b = node.Optional("backlash_deg"))
    e.backlash = Radians(b->InRange(b->AsDouble(), 0, 10));
  if (auto j = node.Optional("jitter_deg")) e.jitter = Radians(j->InRange(j->AsDouble(), 0, 10));
  return e;
}

}  // namespace

double ResponseCurveEffect::Apply(double linear) const {
  const double x = std::clamp(linear, 0.0, 1.0);
  switch (curve) {
    case Curve::kSrgb:
      return SrgbEncode(x);
    case Curve::kGamma:
      return std::pow(x, 1.0 / gamma);
    case Curve::kTable: {
      const double t = x * static_cast<double>(table.size() - 1);
      const std::size_t i = std::min(static_cast<std::size_t>(t), table.size() - 2);
      const double frac = t - static_cast<double>(i);
      return table[i] + frac * (table[i + 1] - table[i]);
    }
  }
  return x;
}

const std::vector<std::string>& KnownEffectNames() {
  static const std::vector<std::string> names = {
      "area_light", "ambient",    "radial_distortion", "vignetting",     "shot_noise",
      "read_noise", "saturation", "quantization",      "response_curve", "mechanical_error"};
  return names;
}

bool Effects::AnySensorEffect() const {
  return vignetting || shot_noise || read_noise || saturation || quantization || response_curve;
}

std::string Effects::Describe() const {
  const bool active[] = {area_light.has_value(),        ambient.has_value(),
                         radial_distortion.has_value(), vignetting.has_value(),
                         shot_noise.has_value(),        read_noise.has_value(),
                         saturation.has_value(),        quantization.has_value(),
                         response_curve.has_value(),    mechanical_error.has_value()};
  std::string out;
  for (std::size_t i = 0; i < KnownEffectNames().size(); ++i) {
    if (active[i]) out += (out.empty() ? "" : ", ") + KnownEffectNames()[i];
  }
  return out.empty() ? "none (ideal camera)" : out;
}

Effects ParseEffects(const YamlNode& list) {
  Effects effects;
  std::set<std::string> seen;
  for (const YamlNode& item : list.Elements()) {
    if (!item.IsMap()) item.Fail("expected a mapping with a 'type' key");
    const YamlNode type = item.Required("type");
    const std::string name = type.AsString();
    const auto& known = KnownEffectNames();
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string all;
      for (const std::string& k : known) all += (all.empty() ? "" : ", ") + k;
      type.Fail("unknown effect '" + name + "' (known: " + all + ")");
    }
    if (!seen.insert(name).second) type.Fail("effect '" + name + "' is listed twice");
    // Values of a disabled effect are still checked: switching it on must not reveal errors.
    const bool enabled = item.Get("enabled", true);
    auto set = [&](auto& slot, auto value) {
      if (enabled) slot = std::move(value);
    };
    if (name == "area_light") set(effects.area_light, ParseAreaLight(item));
    if (name == "ambient") set(effects.ambient, ParseAmbient(item));
    if (name == "radial_distortion") set(effects.radial_distortion, ParseRadialDistortion(item));
    if (name == "vignetting") set(effects.vignetting, ParseVignetting(item));
    if (name == "shot_noise") set(effects.shot_noise, ParseShotNoise(item));
    if (name == "read_noise") set(effects.read_noise, ParseReadNoise(item));
    if (name == "saturation") set(effects.saturation, ParseSaturation(item));
    if (name == "quantization") set(effects.quantization, ParseQuantization(item));
    if (name == "response_curve") set(effects.response_curve, ParseResponseCurve(item));
    if (name == "mechanical_error") set(effects.mechanical_error, ParseMechanicalError(item));
    item.Finish();
  }
  return effects;
}

}  // namespace brdfrig::sim
