// The seed's compact BRDF model. A *slice* fixes the incidence angle theta_in; within a slice
// the BRDF is a surface of revolution around the mirror direction r = 2(n·l)n − l, so per
// colour channel it is a function of theta = angle(v, r):
//
//     f(theta) = A2 + (A1 − A2) / (1 + exp((theta − x0) / h))
//
// A model is a set of slices at strictly increasing theta_in knots. Between knots the
// per-slice values at the query theta are interpolated across theta_in with a monotone C1
// cubic (Fritsch–Carlson PCHIP): C1 like the seed asks, and it never overshoots the values at
// the two neighbouring knots, so it cannot go negative. Outside the knot range the nearest
// slice is used unchanged (constant extrapolation in theta_in).
#pragma once

#include <array>
#include <vector>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

// Parameters of one channel of one slice. Angles in radians.
struct LobeParams {
  double a1 = 0;  // peak value at the mirror direction (1/sr)
  double a2 = 0;  // floor far from the mirror direction (1/sr)
  double h = 1;   // softness (radians), > 0
  double x0 = 0;  // half-width angle of the lobe (radians)
};

struct Slice {
  double theta_in = 0;                // incidence angle of the slice (radians)
  std::array<LobeParams, 3> channel;  // R, G, B
};

// The two angles the model depends on.
struct SliceAngles {
  double theta_in = 0;  // angle between n and l
  double theta = 0;     // angle between v and the mirror direction of l about n
};

// Computes theta_in and theta with formulas that stay accurate at 0 and near 90°.
SliceAngles ComputeSliceAngles(const Vec3& l, const Vec3& v, const Vec3& n);

// The logistic lobe of one channel, evaluated without overflow for any finite parameters.
double EvalLobe(const LobeParams& p, double theta);

enum class Interpolation { kSpline, kLinear };

// The most slices a model may have, what the renderer holds (render/gpu_material.h), and the
// least spacing of their theta_in knots: float (the GPU's spline) must tell them apart, and the
// seed fit pools positions closer than 0.1° into one slice anyway.
inline constexpr int kMaxSlices = 64;
inline constexpr double kMinKnotSpacing = 1e-4;  // radians

class SliceModel : public Brdf {
 public:
  // Validates (throws brdfrig::Error naming the slice and field): at least one slice, all
  // values finite, a1 >= a2 >= 0, h > 0, theta_in in [0, pi/2], knots increasing by at least
  // kMinKnotSpacing, at most kMaxSlices slices.
  explicit SliceModel(std::vector<Slice> slices);

  Rgb Eval(const Vec3& l, const Vec3& v, const Vec3& n) const override;
  std::string Name() const override;

  // The model as a function of its two angles (theta_in, theta >= 0).
  Rgb EvalAngles(double theta_in, double theta,
                 Interpolation interpolation = Interpolation::kSpline) const;

  const std::vector<Slice>& slices() const { return slices_; }

 private:
  std::vector<Slice> slices_;
};

}  // namespace brdfrig::brdf
