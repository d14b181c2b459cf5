// The scene's `effects:` list: everything that makes the simulated camera less than ideal.
// Only listed (and not `enabled: false`) effects are simulated; an absent effect is an empty
// std::optional and costs nothing. Whatever order the file lists them in, they are applied in
// the physical order:
//
//   world   area_light, ambient                  (change the radiance leaving the scene)
//   optics  radial_distortion, vignetting        (where a ray goes; light lost towards corners)
//   sensor  shot_noise, read_noise, saturation, quantization
//   camera  response_curve                       (in-camera tone curve, e.g. for JPEG)
//   rig     mechanical_error                     (axis backlash and jitter, see world.h)
//
// Keys of each effect are documented in docs/sim_scene.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "common/yaml_reader.h"

namespace brdfrig::sim {

// A finite light: `samples` isotropic emitters on a disk of `radius` facing the origin, each
// with 1/samples of the intensity (softens sharp highlights; far away it is the point light).
struct AreaLightEffect {
  double radius = 0.01;  // metres
  int samples = 16;
};

// Uniform sky of `radiance` over the upper hemisphere: adds radiance × directional albedo.
struct AmbientEffect {
  brdf::Rgb radiance = brdf::Rgb::Zero();  // W/(m² sr)
};

// OpenCV radial model x_d = x_u (1 + k1 r² + k2 r⁴), used to trace the rays of every pixel.
struct RadialDistortionEffect {
  double k1 = 0, k2 = 0;
};

// Light lost towards the image corners: cos⁴ of the off-axis angle (natural vignetting), or a
// polynomial 1 + a1 r² + a2 r⁴ in r = distance from the principal point / half diagonal.
struct VignettingEffect {
  enum class Falloff { kCos4, kPolynomial } falloff = Falloff::kCos4;
  double a1 = 0, a2 = 0;
};

// Photon shot noise: the signal (1 = full scale) holds `full_well` electrons; the count is
// Poisson distributed.
struct ShotNoiseEffect {
  double full_well = 20000;
};

// Additive Gaussian read noise, standard deviation in full-scale units.
struct ReadNoiseEffect {
  double sigma = 0.001;
};

// Clipping: values above `level` (full-scale units) are cut to `level`.
struct SaturationEffect {
  double level = 1.0;
};

// The ADC: clamps to [0, 1] and rounds to 2^bits − 1 levels.
struct QuantizationEffect {
  int bits = 12;
};

// The in-camera tone curve from linear [0, 1] to encoded [0, 1]; input is clamped to [0, 1].
struct ResponseCurveEffect {
  enum class Curve { kSrgb, kGamma, kTable } curve = Curve::kSrgb;
  double gamma = 2.2;         // kGamma: out = in^(1/gamma)
  std::vector<double> table;  // kTable: values at equally spaced inputs 0 .. 1, non-decreasing
  double Apply(double linear) const;
};

// Axis mechanics: backlash (the arm lags by backlash/2 behind the motor, on the side it came
// from) and Gaussian position jitter per move (seeded). Radians.
struct MechanicalErrorEffect {
  double backlash = 0;
  double jitter = 0;
};

struct Effects {
  std::optional<AreaLightEffect> area_light;
  std::optional<AmbientEffect> ambient;
  std::optional<RadialDistortionEffect> radial_distortion;
  std::optional<VignettingEffect> vignetting;
  std::optional<ShotNoiseEffect> shot_noise;
  std::optional<ReadNoiseEffect> read_noise;
  std::optional<SaturationEffect> saturation;
  std::optional<QuantizationEffect> quantization;
  std::optional<ResponseCurveEffect> response_curve;
  std::optional<MechanicalErrorEffect> mechanical_error;

  // Whether any effect acting after exposure (vignetting .. response_curve) is active.
  bool AnySensorEffect() const;
  // Names of the active effects in physical order, e.g. "vignetting, shot_noise".
  std::string Describe() const;
};

// Every effect name the scene format knows, in physical order.
const std::vector<std::string>& KnownEffectNames();

// Parses the `effects:` list. Unknown names, duplicates, unknown keys and bad values are
// FileErrors pointing at the offending line.
Effects ParseEffects(const YamlNode& list);

}  // namespace brdfrig::sim
