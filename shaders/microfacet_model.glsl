// The ladder's microfacet rungs, the same formulas as brdf/microfacet_terms.h (the CPU reference,
// brdf/microfacet_model.cc):
//     f = rho_d / pi + F(theta_d) · D(theta_h) · G1(cos_i) G1(cos_o) / (4 cos_i cos_o)
// One program per distribution (MICROFACET_GGX, MICROFACET_BECKMANN or MICROFACET_TABLE), so no
// pixel branches on the kind; the table needs one index computation and one interpolation.
//
// Float care, where the CPU works in double:
// - sin²(theta_h) comes from |n × h|², not 1 − cos²: near the mirror direction 1 − cos² loses
//   every digit a sharp lobe needs, and theta_h = atan(|n × h|, n · h) is accurate at 0 where
//   acos is not (acos(1 − 6e-8) is already 3.5e-4 rad).
// - G1/cos is evaluated as one expression, so a grazing cos never divides 0 by 0.
layout(std140, binding = 0) uniform MicrofacetBlock {
  vec4 uLogD[MAX_TABLE_KNOTS / 4];           // normalized ln D at the table knots, four per vec4
  vec4 uFresnelKnots[MAX_FRESNEL_KNOTS / 4];  // ln F multiplier at equal theta_d steps
  vec4 uDiffuse;                             // rgb: rho_d / pi
  vec4 uF0;                                  // rgb: Schlick reflectance at normal incidence
  // x: alpha² of D (the table: of its GGX tail), y: alpha² of G (the table: shadowing alpha),
  // z: alpha of D (Beckmann's G1 needs it unsquared)
  vec4 uRoughness;
  // x: 1 / max_theta_h, y: knots − 1, z: max_theta_h,
  // w: D at max_theta_h times (alpha² cos² + sin²)² there (the tail's scale)
  vec4 uTable;
  // x: fresnel knot count, y: (count − 1) / (pi / 2)
  vec4 uFresnel;
};

const float kPi = 3.14159265358979;

float tableKnot(int k) { return uLogD[k >> 2][k & 3]; }
float fresnelKnot(int k) { return uFresnelKnots[k >> 2][k & 3]; }

// D(theta_h) given cos and sin² of theta_h.
float distribution(float cosH, float sin2H) {
#if defined(MICROFACET_GGX)
  float a2 = uRoughness.x;
  float denom = a2 * cosH * cosH + sin2H;
  return a2 / (kPi * denom * denom);
#elif defined(MICROFACET_BECKMANN)
  float a2 = uRoughness.x;
  // cos² >= 1e-15 keeps cos⁴ a normal float: the exp is then 0 and the result 0, never 0/0.
  float c2 = max(cosH * cosH, 1e-15);
  return exp(-sin2H / (c2 * a2)) / (kPi * a2 * c2 * c2);
#elif defined(MICROFACET_TABLE)
  // Below 0.1 rad, asin's series (relative error < 1e-7): llvmpipe's atan is accurate in
  // absolute terms only, and the sqrt-spaced knots magnify relative errors of a small theta_h.
  float sinH = sqrt(sin2H);
  float thetaH = sin2H < 0.01 ? sinH * (1.0 + sin2H * (1.0 / 6.0 + sin2H * (3.0 / 40.0)))
                              : atan(sinH, cosH);
  float x = sqrt(thetaH * uTable.x) * uTable.y;
  int k = min(int(x), int(uTable.y) - 1);
  float logD = mix(tableKnot(k), tableKnot(k + 1), x - float(k));
  // Beyond max_theta_h: the GGX tail, continuous with the table's last knot, as a ratio of GGX
  // denominators (no log: both sides of a select are computed on a SIMD rasterizer).
  float denom = uRoughness.x * cosH * cosH + sin2H;
  // A hand-written table may exceed float's range; exp(88) is finite.
  return thetaH >= uTable.z ? uTable.w / (denom * denom) : exp(min(logD, 88.0));
#endif
}

// Smith G1(cos) / cos.
float maskingOverCos(float c) {
#if defined(MICROFACET_BECKMANN)
  // Walter et al.'s rational fit in a = cot / alpha, divided by cos analytically.
  // At the normal (sin 0) a is huge and G1 is 1, as on the CPU.
  float s = sqrt(max(0.0, 1.0 - c * c));
  float a = c / (uRoughness.z * max(s, 1e-30));
  if (a >= 1.6) return 1.0 / c;
  return (3.535 + 2.181 * a) / (uRoughness.z * s * (1.0 + 2.276 * a + 2.577 * a * a));
#else
  float a2 = uRoughness.y;
  return 2.0 / (c + sqrt(a2 * (1.0 - c * c) + c * c));
#endif
}

// exp(c(theta_d)): linear in theta_d between the knots.
float fresnelCorrection(float cosD, vec3 l, vec3 h) {
  int count = int(uFresnel.x);
  if (count == 0) return 1.0;
  if (count == 1) return exp(fresnelKnot(0));
  float thetaD = atan(length(cross(l, h)), cosD);
  float x = clamp(thetaD * uFresnel.y, 0.0, uFresnel.x - 1.0);
  int k = min(int(x), count - 2);
  return exp(mix(fresnelKnot(k), fresnelKnot(k + 1), x - float(k)));
}

vec3 evalMaterial(vec3 l, vec3 v, vec3 n) {
  float cosI = dot(n, l), cosO = dot(n, v);
  if (cosI <= 0.0 || cosO <= 0.0) return vec3(0.0);
  vec3 sum = l + v;
  float norm2 = dot(sum, sum);
  if (norm2 < 1e-30) return uDiffuse.rgb;
  vec3 h = sum * inversesqrt(norm2);
  vec3 nxh = cross(n, h);
  float cosH = min(dot(n, h), 1.0);
  float cosD = clamp(dot(l, h), 0.0, 1.0);
  float spec = distribution(cosH, dot(nxh, nxh)) * maskingOverCos(cosI) *
               maskingOverCos(cosO) * 0.25;
  float m = 1.0 - cosD, m2 = m * m;
  vec3 fresnel = uF0.rgb + (1.0 - uF0.rgb) * (m2 * m2 * m);
  return uDiffuse.rgb + fresnel * (fresnelCorrection(cosD, l, h) * spec);
}
