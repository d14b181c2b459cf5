// The glTF 2.0 metal-rough BRDF (the specification's Appendix B) with KHR_materials_ior and
// KHR_materials_specular, written once as templates so that the CPU model (double), the Ceres
// fits (ceres::Jet) and, line by line, shaders/gltf_model.glsl evaluate the same formulas:
//
//   alpha      = roughness²
//   D          = alpha² / (pi ((n·h)² (alpha² − 1) + 1)²)                       (GGX)
//   V          = 1 / ((n·l + sqrt(alpha² + (1 − alpha²)(n·l)²))
//                     (n·v + sqrt(alpha² + (1 − alpha²)(n·v)²)))     (height-correlated Smith,
//                                                                     G / (4 n·l n·v) in one)
//   x          = (1 − |v·h|)^5                                                  (Schlick)
//   metal      = (baseColor + (1 − baseColor) x) · V · D
//   f0_d       = min(((ior − 1)/(ior + 1))² · specularColor, 1)                (per channel)
//   F_d        = f0_d + (1 − f0_d) x
//   dielectric = (1 − specular · max_c F_d) · baseColor / pi + specular · F_d · V · D
//   f          = mix(dielectric, metal, metallic)
//
// KHR_materials_specular's fresnel_mix weights the diffuse by one minus the largest channel of
// the scaled Fresnel, so a coloured specular never makes a channel brighter than white light
// would. The geometry (cosines) is double; the parameters are T.
#pragma once

#include <algorithm>
#include <cmath>

namespace brdfrig::brdf::gltf {

template <typename T>
T D(double n_dot_h, const T& alpha) {
  const T a2 = alpha * alpha;
  const T denom = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (M_PI * denom * denom);
}

// Height-correlated Smith visibility V = G2 / (4 n·l n·v), as Appendix B writes it.
template <typename T>
T V(double n_dot_l, double n_dot_v, const T& alpha) {
  using std::sqrt;
  const T a2 = alpha * alpha;
  const T gl = n_dot_l + sqrt(a2 + (1.0 - a2) * (n_dot_l * n_dot_l));
  const T gv = n_dot_v + sqrt(a2 + (1.0 - a2) * (n_dot_v * n_dot_v));
  return 1.0 / (gl * gv);
}

inline double SchlickWeight(double v_dot_h) {
  const double m = 1 - std::clamp(std::abs(v_dot_h), 0.0, 1.0);
  const double m2 = m * m;
  return m2 * m2 * m;
}

// f0 of an ior against air, ((ior − 1)/(ior + 1))².
template <typename T>
T IorF0(const T& ior) {
  const T r = (ior - 1.0) / (ior + 1.0);
  return r * r;
}

// The parameters of one evaluation, T for each number a fit may vary.
template <typename T>
struct Params {
  T base_color[3];
  T metallic, roughness, ior, specular;
  T specular_color[3];
};

// f for unit l, v above the surface (n·l > 0, n·v > 0); out[3] gets R, G, B (1/sr).
template <typename T>
void Eval(const Params<T>& p, double n_dot_l, double n_dot_v, double n_dot_h, double v_dot_h,
          T out[3]) {
  const T alpha = p.roughness * p.roughness;
  const T vd = V(n_dot_l, n_dot_v, alpha) * D(n_dot_h, alpha);
  const double x = SchlickWeight(v_dot_h);
  const T ior_f0 = IorF0(p.ior);
  T fd[3];
  T fd_max(0.0);
  for (int c = 0; c < 3; ++c) {
    T f0 = ior_f0 * p.specular_color[c];
    if (f0 > 1.0) f0 = T(1.0);  // min(·, 1), with the derivative of the branch taken
    fd[c] = f0 + (1.0 - f0) * x;
    if (c == 0 || fd[c] > fd_max) fd_max = fd[c];
  }
  const T diffuse_weight = 1.0 - p.specular * fd_max;
  for (int c = 0; c < 3; ++c) {
    const T dielectric = diffuse_weight * p.base_color[c] * (1.0 / M_PI) + p.specular * fd[c] * vd;
    const T metal = (p.base_color[c] + (1.0 - p.base_color[c]) * x) * vd;
    out[c] = (1.0 - p.metallic) * dielectric + p.metallic * metal;
  }
}

}  // namespace brdfrig::brdf::gltf
