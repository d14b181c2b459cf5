// The measured prior's table (kind `prior`): q = ln(f·c + eps) on a Rusinkiewicz grid, the same
// function as the CPU reference brdf::RusinkiewiczTable::Eval (brdf/rusinkiewicz_table.cc):
// theta_h on sqrt-spaced nodes, theta_d and phi_d (folded into [0, pi/2]) on even nodes, q
// interpolated trilinearly on the continuous index coordinates, then
//     f = max(exp(q) − eps, 0) / c,   c = max(cos_i, floor) · max(cos_o, floor).
// The interpolation is done here from eight texelFetch reads, not by the sampler: hardware
// filtering quantizes its weights (8 bits), which would break agreement with the CPU. The nodes
// are an RGBA32F buffer texture in the CPU's node order ((ih·theta_d + id)·phi_d + ip): on
// llvmpipe its eight fetches cost about half of what a 3D texture's do (docs/render.md).
//
// No tangent frame: theta_h, theta_d and |phi_d| depend only on n, l and v. With h the half
// vector, y = n × h (|y| = sin theta_h) and x = y × h span the plane normal to h exactly as the
// CPU's rotation R_y(−theta_h) R_z(−phi_h) does, so |phi_d| = atan(|l·y|, |l·x|) (the fold to
// [0, pi/2] included). Only at h = n exactly, where phi_h is undefined, the CPU's tangent frame
// is used (brdf/rusinkiewicz_table.cc's ToLocal), so that the mirror direction agrees too.
//
// Float care, where the CPU works in double (as in shaders/microfacet_model.glsl):
// - theta_h comes from |n × h| (asin's series below 0.1 rad, atan above), never acos(n·h):
//   acos near 1 loses every digit, and the sqrt-spaced index magnifies a small theta_h's
//   relative error; theta_d = atan(|l × h|, l·h).
// - atan is our own (atanAccurate): llvmpipe's is accurate only to ~3e-6 rad.
uniform samplerBuffer uTable;  // q of node (ih·theta_d + id)·phi_d + ip -> rgb
// Continuous index per unit of (phi_d, theta_d, sqrt(theta_h)): (nodes − 1) / (pi/2) for the
// even axes, (nodes − 1) / sqrt(pi/2) for theta_h.
uniform vec3 uTableScale;
uniform vec3 uTableLast;       // nodes − 1 along (phi_d, theta_d, theta_h)
uniform int uTableStrideD;     // phi_d: the node offset of one theta_d step
uniform int uTableStrideH;     // theta_d · phi_d: the node offset of one theta_h step
uniform float uTableEpsilon;   // the mapping's eps
uniform float uTableCosFloor;  // the floor of each cosine in c

// atan(y, x) for y, x >= 0 to ~1e-7 absolute: llvmpipe's atan is off by up to ~3e-6 rad, which
// moves a theta_d index by 5e-5 of a cell and f by ~1e-4 on a sharp lobe. Abramowitz & Stegun
// 4.4.49 on [0, 1] (error <= 2e-8), one division. atan(0, 0) = 0, as the CPU's atan2 (GLSL's
// is undefined there; phi_d at l = h, where theta_d = 0 and phi_d does not matter).
float atanAccurate(float y, float x) {
  bool swap = y > x;
  float r = swap ? x / y : y / max(x, 1e-30);
  float r2 = r * r;
  float a = r * (0.9999993329 + r2 * (-0.3332985605 + r2 * (0.1994653599 + r2 * (-0.1390853351 +
            r2 * (0.0964200441 + r2 * (-0.0559098861 + r2 * (0.0218612288 +
            r2 * -0.0040540580)))))));
  return swap ? 1.5707963 - a : a;
}

vec3 tableNode(int node) { return texelFetch(uTable, node).rgb; }

vec3 evalMaterial(vec3 l, vec3 v, vec3 n) {
  float cosI = dot(n, l), cosO = dot(n, v);
  if (cosI <= 0.0 || cosO <= 0.0) return vec3(0.0);
  vec3 sum = l + v;
  float norm2 = dot(sum, sum);
  vec3 h = norm2 > 0.0 ? sum * inversesqrt(norm2) : n;
  vec3 y = cross(n, h);
  float sin2H = dot(y, y);
  float sinH = sqrt(sin2H);
  float thetaH = sin2H < 0.01 ? sinH * (1.0 + sin2H * (1.0 / 6.0 + sin2H * (3.0 / 40.0)))
                              : atanAccurate(sinH, dot(n, h));
  float thetaD = atanAccurate(length(cross(l, h)), max(dot(l, h), 0.0));
  // h = n: the CPU's tangent t = normalize(n × helper), so x = t and y = n × t, which is
  // n (n·helper) − helper up to its length (only the ratio of l·y and l·x counts).
  bool useX = abs(n.x) < 0.9;
  y = sin2H == 0.0 ? n * (useX ? n.x : n.y) - vec3(useX ? 1.0 : 0.0, useX ? 0.0 : 1.0, 0.0) : y;
  vec3 x = cross(y, h);
  float phiD = atanAccurate(abs(dot(l, y)), abs(dot(l, x)));

  vec3 u = clamp(vec3(phiD, thetaD, sqrt(thetaH)) * uTableScale, vec3(0.0), uTableLast);
  ivec3 i = min(ivec3(u), ivec3(uTableLast) - 1);
  vec3 t = u - vec3(i);
  int k = (i.z * uTableStrideH) + i.y * uTableStrideD + i.x;
  int kd = k + uTableStrideD, kh = k + uTableStrideH, khd = kh + uTableStrideD;
  vec3 q00 = mix(tableNode(k), tableNode(k + 1), t.x);
  vec3 q10 = mix(tableNode(kd), tableNode(kd + 1), t.x);
  vec3 q01 = mix(tableNode(kh), tableNode(kh + 1), t.x);
  vec3 q11 = mix(tableNode(khd), tableNode(khd + 1), t.x);
  vec3 q = mix(mix(q00, q10, t.y), mix(q01, q11, t.y), t.z);
  float c = max(cosI, uTableCosFloor) * max(cosO, uTableCosFloor);
  return max(exp(q) - uTableEpsilon, vec3(0.0)) / c;
}
