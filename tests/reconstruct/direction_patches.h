// Synthetic direction samples shaped like photos of the rig: each "patch" is what a 10 cm
// cut-out shows from a camera 0.5 m and a light 0.6 m away (a grid of plane points, each with
// its own l and v), evaluated from a known BRDF with seeded multiplicative noise.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "brdf/brdf.h"
#include "reconstruct/direction_samples.h"

namespace brdfrig::reconstruct::testing {

struct PatchDesign {
  double camera_deg;             // camera elevation from the normal, towards +x
  double light_deg;              // light elevation, towards −x (negative: the camera's side)
  double light_azimuth_deg = 0;  // light turned about the normal
};

// Mirror at 15° and 45°; off-specular at theta_h ≈ 10°, 25°, 45°; the light 90° out of plane.
inline std::vector<PatchDesign> DesignedPatches() {
  return {{15, 15}, {45, 45}, {35, 15}, {60, 10}, {70, -20}, {30, 30, 90}};
}

inline DirectionSamples Patch(const brdf::Brdf& truth, const PatchDesign& d, int grid = 40,
                              double noise = 0.01, unsigned seed = 1) {
  const double deg = M_PI / 180;
  const brdf::Vec3 camera =
      0.5 * brdf::Vec3(std::sin(d.camera_deg * deg), 0, std::cos(d.camera_deg * deg));
  const double a = d.light_azimuth_deg * deg;
  // In the camera's plane on the far side (azimuth 180°), then turned by light_azimuth.
  const double sin_l = std::sin(d.light_deg * deg);
  const brdf::Vec3 light =
      0.6 * brdf::Vec3(-sin_l * std::cos(a), -sin_l * std::sin(a), std::cos(d.light_deg * deg));
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0, 1);
  DirectionSamples out;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      const brdf::Vec3 p(0.1 * ((i + 0.5) / grid - 0.5), 0.1 * ((j + 0.5) / grid - 0.5), 0);
      DirectionSample s;
      s.l = (light - p).normalized();
      s.v = (camera - p).normalized();
      const brdf::Rgb f = truth.Eval(s.l, s.v, brdf::Vec3::UnitZ());
      for (int c = 0; c < 3; ++c) s.f[c] = f[c] * (1 + noise * gauss(rng));
      s.weight = 1;
      out.samples.push_back(s);
    }
  }
  out.pixels_used = grid * grid;
  return out;
}

inline std::vector<DirectionSample> AllPatches(const brdf::Brdf& truth,
                                               const std::vector<PatchDesign>& designs) {
  std::vector<DirectionSample> all;
  unsigned seed = 1;
  for (const PatchDesign& d : designs) {
    const DirectionSamples p = Patch(truth, d, 40, 0.01, seed++);
    all.insert(all.end(), p.samples.begin(), p.samples.end());
  }
  return all;
}

}  // namespace brdfrig::reconstruct::testing
