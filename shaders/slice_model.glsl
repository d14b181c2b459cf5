// The seed's slice model, the same algorithm as brdf/slice_model.cc (the CPU reference):
// per slice and channel f(theta) = A2 + (A1 - A2) / (1 + exp((theta - x0) / h)), interpolated
// across theta_in with a monotone C1 cubic (Fritsch–Carlson), constant outside the knots.

// Parameters live in a uniform block (cheaper than texture fetches on a software rasterizer).
layout(std140, binding = 0) uniform SliceBlock {
  vec4 uSliceParams[4 * MAX_SLICES];  // slice k: [4k] A1, [4k+1] A2, [4k+2] log2(e)/h, [4k+3] x0 (rgb)
  vec4 uKnots[MAX_SLICES / 4];        // theta_in knots, four per vec4
  int uSliceCount;
  int uLinear;  // plain linear interpolation, to show the seams the seed warns about
};

float knot(int k) { return uKnots[k >> 2][k & 3]; }

// Logistic for three channels at once. Clamping t to ±126 keeps 2^t finite (no inf/NaN for any
// h), and the clamp changes the result only where the logistic is below 2^-126 of A1 − A2.
vec3 sliceValue(int k, float theta) {
  vec3 a1 = uSliceParams[4 * k].rgb;
  vec3 a2 = uSliceParams[4 * k + 1].rgb;
  // t is (theta − x0)/h in base-2 units: the buffer holds log2(e)/h, so exp2 needs no scaling.
  vec3 t = (theta - uSliceParams[4 * k + 3].rgb) * uSliceParams[4 * k + 2].rgb;
  return a2 + (a1 - a2) / (1.0 + exp2(clamp(t, -126.0, 126.0)));
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
  // Interval [i, i+1] holding thetaIn (clamped to the end intervals).
  int i = 0;
  for (int k = 1; k < n - 1; ++k) i += int(knot(k) <= thetaIn);
  // Every slice is evaluated with a uniform index and the four neighbours are picked by
  // selects: on a SIMD rasterizer (llvmpipe, GPUs) this avoids per-pixel gathers and divergent
  // branches, which cost far more than the extra logistic evaluations.
  vec3 yPrev = vec3(0.0), y0 = vec3(0.0), y1 = vec3(0.0), yNext = vec3(0.0);
  float tPrev = 0.0, t0 = 0.0, t1 = 0.0, tNext = 0.0;
  for (int k = 0; k < n; ++k) {
    vec3 y = sliceValue(k, theta);
    float t = knot(k);
    bool isPrev = k == i - 1, is0 = k == i, is1 = k == i + 1, isNext = k == i + 2;
    yPrev = isPrev ? y : yPrev;
    tPrev = isPrev ? t : tPrev;
    y0 = is0 ? y : y0;
    t0 = is0 ? t : t0;
    y1 = is1 ? y : y1;
    t1 = is1 ? t : t1;
    yNext = isNext ? y : yNext;
    tNext = isNext ? t : tNext;
  }
  if (n == 1) return y0;
  float h = t1 - t0;
  // Clamping s gives the constant extrapolation outside the knots: the cubic below is exactly
  // y0 at s = 0 and y1 at s = 1.
  float s = clamp((thetaIn - t0) / h, 0.0, 1.0);
  if (uLinear != 0 || n == 2) return y0 + s * (y1 - y0);
  bool hasPrev = i > 0, hasNext = i + 2 < n;
  float hp = hasPrev ? t0 - tPrev : 1.0;
  float hn = hasNext ? tNext - t1 : 1.0;
  vec3 delta = (y1 - y0) / h;
  vec3 deltaP = (y0 - yPrev) / hp;
  vec3 deltaN = (yNext - y1) / hn;
  vec3 m0 = hasPrev ? interiorSlope(hp, h, deltaP, delta) : endSlope(h, hn, delta, deltaN);
  vec3 m1 = hasNext ? interiorSlope(h, hn, delta, deltaN) : endSlope(h, hp, delta, deltaP);
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
