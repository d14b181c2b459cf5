// The `gltf` kind: glTF 2.0's metal-rough BRDF (Appendix B) with KHR_materials_ior and
// KHR_materials_specular, the same formulas as brdf/gltf_terms.h (the CPU reference,
// brdf/gltf_model.cc):
//   metal      = (baseColor + (1 − baseColor) x) · V · D,      x = (1 − |v·h|)^5
//   dielectric = (1 − specular · max(F_d)) · baseColor / pi + specular · F_d · V · D,
//                F_d = f0_d + (1 − f0_d) x, f0_d = min(((ior − 1)/(ior + 1))² specularColor, 1)
//   f          = mix(dielectric, metal, metallic)
// What the renderer would recompute per pixel (f0_d, baseColor / pi, alpha²) comes from the
// CPU in double (render/gpu_material.cc).
//
// Float care: D's denominator (n·h)²(alpha² − 1) + 1 is written alpha² cos² + sin² with
// sin²(theta_h) = |n × h|², so a sharp lobe keeps its digits at the mirror direction.
uniform vec3 uGltfBase;       // baseColor
uniform vec3 uGltfDiffuse;    // baseColor / pi
uniform vec3 uGltfF0;         // the dielectric f0_d (clamped to 1)
uniform float uGltfMetallic;
uniform float uGltfSpecular;
uniform float uGltfAlpha2;    // alpha² = roughness⁴

const float kGltfPi = 3.14159265358979;

vec3 evalMaterial(vec3 l, vec3 v, vec3 n) {
  float cosI = dot(n, l), cosO = dot(n, v);
  if (cosI <= 0.0 || cosO <= 0.0) return vec3(0.0);
  float metallic = uGltfMetallic, specular = uGltfSpecular, a2 = uGltfAlpha2;
  vec3 sum = l + v;
  float norm2 = dot(sum, sum);
  vec3 h = norm2 < 1e-30 ? n : sum * inversesqrt(norm2);
  vec3 nxh = cross(n, h);
  float cosH = min(dot(n, h), 1.0);
  float denom = a2 * cosH * cosH + dot(nxh, nxh);
  float d = a2 / (kGltfPi * denom * denom);
  float vis = 1.0 / ((cosI + sqrt(a2 + (1.0 - a2) * cosI * cosI)) *
                     (cosO + sqrt(a2 + (1.0 - a2) * cosO * cosO)));
  float m = 1.0 - clamp(abs(dot(v, h)), 0.0, 1.0), m2 = m * m;
  float x = m2 * m2 * m;
  vec3 fd = uGltfF0 + (1.0 - uGltfF0) * x;
  float fdMax = max(fd.r, max(fd.g, fd.b));
  float vd = vis * d;
  vec3 dielectric = (1.0 - specular * fdMax) * uGltfDiffuse + specular * fd * vd;
  vec3 metal = (uGltfBase + (1.0 - uGltfBase) * x) * vd;
  return mix(dielectric, metal, metallic);
}
