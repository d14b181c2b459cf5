// The seed's slice model, the same algorithm as brdf/slice_model.cc (the CPU reference):
// per slice and channel f(theta) = A2 + (A1 - A2) / (1 + exp((theta - x0) / h)), interpolated
// across theta_in with a monotone C1 cubic (Fritsch–Carlson), constant outside the knots.
// Slices live in uSlices: texel (p, k) holds parameter p (0 A1, 1 A2, 2 h, 3 x0) of slice k
// for the three channels (r, g, b).

uniform sampler2D uSlices;
uniform float uKnots[MAX_SLICES];
uniform int uSliceCount;
uniform bool uLinear;  // plain linear interpolation, to show the seams the seed warns about

// Stable logistic for three channels at once: exp() only ever sees a non-positive argument.
vec3 sliceValue(int k, float theta) {
  vec3 a1 = texelFetch(uSlices, ivec2(0, k), 0).rgb;
  vec3 a2 = texelFetch(uSlices, ivec2(1, k), 0).rgb;
  vec3 h = texelFetch(uSlices, ivec2(2, k), 0).rgb;
  vec3 x0 = texelFetch(uSlices, ivec2(3, k), 0).rgb;
  vec3 t = (theta - x0) / h;
  vec3 e = exp(-abs(t));
  vec3 s = mix(1.0 / (1.0 + e), e / (1.0 + e), step(vec3(0.0), t));
  return a2 + (a1 - a2) * s;
}

vec3 interiorSlope(float h0, float h1, vec3 d0, vec3 d1) {
  float w0 = 2.0 * h1 + h0, w1 = h1 + 2.0 * h0;
  vec3 harmonic = (w0 + w1) / (w0 / d0 + w1 / d1);
  return mix(vec3(0.0), harmonic, greaterThan(d0 * d1, vec3(0.0)));
}

vec3 endSlope(float h0, float h1, vec3 d0, vec3 d1) {
  vec3 d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  d = mix(d, vec3(0.0), lessThanEqual(d * d0, vec3(0.0)));
  bvec3 limit = bvec3(vec3(lessThanEqual(d0 * d1, vec3(0.0))) *
                      vec3(greaterThan(abs(d), 3.0 * abs(d0))));
  return mix(d, 3.0 * d0, limit);
}

vec3 evalSliceModel(float thetaIn, float theta) {
  int n = uSliceCount;
  if (n == 1 || thetaIn <= uKnots[0]) return sliceValue(0, theta);
  if (thetaIn >= uKnots[n - 1]) return sliceValue(n - 1, theta);
  int i = 0;
  while (i + 2 < n && uKnots[i + 1] <= thetaIn) ++i;
  float t0 = uKnots[i], t1 = uKnots[i + 1], h = t1 - t0;
  float s = (thetaIn - t0) / h;
  vec3 y0 = sliceValue(i, theta), y1 = sliceValue(i + 1, theta);
  if (uLinear || n == 2) return y0 + s * (y1 - y0);
  // Each neighbouring slice is evaluated once: at most four per fragment.
  vec3 delta = (y1 - y0) / h;
  float hp = i > 0 ? t0 - uKnots[max(i - 1, 0)] : 0.0;
  float hn = i + 2 < n ? uKnots[min(i + 2, n - 1)] - t1 : 0.0;
  vec3 deltaP = i > 0 ? (y0 - sliceValue(i - 1, theta)) / hp : vec3(0.0);
  vec3 deltaN = i + 2 < n ? (sliceValue(i + 2, theta) - y1) / hn : vec3(0.0);
  vec3 m0 = i > 0 ? interiorSlope(hp, h, deltaP, delta) : endSlope(h, hn, delta, deltaN);
  vec3 m1 = i + 2 < n ? interiorSlope(h, hn, delta, deltaN) : endSlope(h, hp, delta, deltaP);
  float s2 = s * s, s3 = s2 * s;
  vec3 result = (2.0 * s3 - 3.0 * s2 + 1.0) * y0 + (s3 - 2.0 * s2 + s) * h * m0 +
                (-2.0 * s3 + 3.0 * s2) * y1 + (s3 - s2) * h * m1;
  return max(result, vec3(0.0));
}

float angleBetween(vec3 a, vec3 b) { return atan(length(cross(a, b)), dot(a, b)); }

vec3 evalMaterial(vec3 l, vec3 v, vec3 n) {
  vec3 mirror = 2.0 * dot(n, l) * n - l;
  return evalSliceModel(angleBetween(n, l), angleBetween(v, mirror));
}
