// Reference BRDFs, the same formulas as brdf/analytic.cc and brdf/merl.cc.
#if defined(MATERIAL_LAMBERT)
uniform vec3 uAlbedo;
vec3 evalMaterial(vec3 l, vec3 v, vec3 n) { return uAlbedo / 3.14159265358979; }

#elif defined(MATERIAL_GGX)
uniform vec3 uDiffuse;
uniform vec3 uF0;
uniform float uAlpha;
vec3 evalMaterial(vec3 l, vec3 v, vec3 n) {
  vec3 h = normalize(l + v);
  float ci = dot(n, l), co = dot(n, v), ch = min(dot(n, h), 1.0), lh = min(dot(l, h), 1.0);
  float a2 = uAlpha * uAlpha;
  float denom = ch * ch * (a2 - 1.0) + 1.0;
  float d = a2 / (3.14159265358979 * denom * denom);
  float g1i = 2.0 * ci / (ci + sqrt(a2 + (1.0 - a2) * ci * ci));
  float g1o = 2.0 * co / (co + sqrt(a2 + (1.0 - a2) * co * co));
  vec3 f = uF0 + (1.0 - uF0) * pow(1.0 - clamp(lh, 0.0, 1.0), 5.0);
  return uDiffuse / 3.14159265358979 + f * (d * g1i * g1o / (4.0 * ci * co));
}

#elif defined(MATERIAL_MERL)
uniform sampler3D uMerl;  // (phi_d, theta_d, theta_h) -> rgb, already scaled to 1/sr
vec3 evalMaterial(vec3 l, vec3 v, vec3 n) {
  // Local frame around n (same construction as the CPU table lookup).
  float sgn = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sgn + n.z);
  float b = n.x * n.y * a;
  vec3 t = vec3(1.0 + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
  vec3 bt = vec3(b, sgn + n.y * n.y * a, -n.y);
  vec3 L = vec3(dot(l, t), dot(l, bt), dot(l, n));
  vec3 V = vec3(dot(v, t), dot(v, bt), dot(v, n));
  vec3 h = normalize(L + V);
  float thetaH = acos(clamp(h.z, -1.0, 1.0));
  float phiH = atan(h.y, h.x);
  float c = cos(-phiH), s = sin(-phiH);
  vec3 d = vec3(c * L.x - s * L.y, s * L.x + c * L.y, L.z);
  c = cos(-thetaH); s = sin(-thetaH);
  d = vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
  float thetaD = acos(clamp(d.z, -1.0, 1.0));
  float phiD = atan(d.y, d.x);
  if (phiD < 0.0) phiD += 3.14159265358979;
  int ih = clamp(int(sqrt(thetaH / 1.5707963267949) * 90.0), 0, 89);
  int id = clamp(int(thetaD / 1.5707963267949 * 90.0), 0, 89);
  int ip = clamp(int(phiD / 3.14159265358979 * 180.0), 0, 179);
  return max(texelFetch(uMerl, ivec3(ip, id, ih), 0).rgb, vec3(0.0));
}
#endif
