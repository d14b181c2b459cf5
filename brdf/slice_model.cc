#include "brdf/slice_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>  // cross()

#include "brdf/logistic.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

// Angle between two vectors via atan2(|a×b|, a·b): accurate near 0 and pi, unlike acos.
double AngleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

[[noreturn]] void Invalid(std::size_t slice, const std::string& field, const std::string& rule,
                          double got) {
  std::ostringstream msg;
  msg.precision(17);
  msg << "slices[" << slice << "]." << field << ": " << rule << ", got " << got;
  throw Error(msg.str());
}

void ValidateSlices(const std::vector<Slice>& slices) {
  if (slices.empty()) throw Error("slices: a model needs at least one slice");
  if (slices.size() > static_cast<std::size_t>(kMaxSlices)) {
    throw Error("slices: at most " + std::to_string(kMaxSlices) + " slices, got " +
                std::to_string(slices.size()));
  }
  for (std::size_t i = 0; i < slices.size(); ++i) {
    const Slice& s = slices[i];
    if (!std::isfinite(s.theta_in)) Invalid(i, "theta_in", "must be finite", s.theta_in);
    if (s.theta_in < 0 || s.theta_in > M_PI / 2) {
      Invalid(i, "theta_in", "must be in [0, pi/2]", s.theta_in);
    }
    if (i > 0 && !(s.theta_in >= slices[i - 1].theta_in + kMinKnotSpacing)) {
      std::ostringstream previous;
      previous.precision(17);
      previous << slices[i - 1].theta_in;
      Invalid(i, "theta_in",
              "must be greater than the previous slice's theta_in (" + previous.str() +
                  ") by at least " + std::to_string(kMinKnotSpacing),
              s.theta_in);
    }
    for (int c = 0; c < 3; ++c) {
      const LobeParams& p = s.channel[c];
      const std::string ch = kChannelNames[c];
      for (const auto& [name, value] :
           {std::pair{"A1", p.a1}, {"A2", p.a2}, {"h", p.h}, {"x0", p.x0}}) {
        if (!std::isfinite(value)) Invalid(i, ch + "." + name, "must be finite", value);
      }
      if (p.a2 < 0) Invalid(i, ch + ".A2", "must be >= 0", p.a2);
      if (p.a1 < p.a2) Invalid(i, ch + ".A1", "must be >= A2 (" + std::to_string(p.a2) + ")", p.a1);
      if (!(p.h > 0)) Invalid(i, ch + ".h", "must be > 0", p.h);
    }
  }
}

// Fritsch–Carlson slope at an interior knot from the two neighbouring secant slopes: zero at a
// local extremum, otherwise a weighted harmonic mean, which keeps every interval monotone.
double InteriorSlope(double h0, double h1, double delta0, double delta1) {
  if (delta0 * delta1 <= 0) return 0;
  const double w0 = 2 * h1 + h0, w1 = h1 + 2 * h0;
  return (w0 + w1) / (w0 / delta0 + w1 / delta1);
}

// One-sided three-point slope at an end knot, limited so the end interval stays monotone.
double EndSlope(double h0, double h1, double delta0, double delta1) {
  double d = ((2 * h0 + h1) * delta0 - h0 * delta1) / (h0 + h1);
  if (d * delta0 <= 0) return 0;
  if (delta0 * delta1 <= 0 && std::abs(d) > 3 * std::abs(delta0)) d = 3 * delta0;
  return d;
}

}  // namespace

SliceAngles ComputeSliceAngles(const Vec3& l, const Vec3& v, const Vec3& n) {
  const Vec3 mirror = 2 * n.dot(l) * n - l;
  return {AngleBetween(n, l), AngleBetween(v, mirror)};
}

double EvalLobe(const LobeParams& p, double theta) {
  const double t = (theta - p.x0) / p.h;
  return p.a2 + (p.a1 - p.a2) * Logistic(-t);
}

SliceModel::SliceModel(std::vector<Slice> slices) : slices_(std::move(slices)) {
  ValidateSlices(slices_);
}

std::string SliceModel::Name() const {
  return "slice_model(" + std::to_string(slices_.size()) + " slices)";
}

Rgb SliceModel::Eval(const Vec3& l, const Vec3& v, const Vec3& n) const {
  if (n.dot(l) <= 0 || n.dot(v) <= 0) return Rgb::Zero();
  const SliceAngles a = ComputeSliceAngles(l, v, n);
  return EvalAngles(a.theta_in, a.theta);
}

Rgb SliceModel::EvalAngles(double theta_in, double theta, Interpolation interpolation) const {
  const std::size_t n = slices_.size();
  auto value = [&](std::size_t k) {
    const Slice& s = slices_[k];
    return Rgb(EvalLobe(s.channel[0], theta), EvalLobe(s.channel[1], theta),
               EvalLobe(s.channel[2], theta));
  };
  // Constant extrapolation outside the knots; a single slice is used everywhere.
  if (n == 1 || theta_in <= slices_.front().theta_in) return value(0);
  if (theta_in >= slices_.back().theta_in) return value(n - 1);

  const auto upper = std::upper_bound(slices_.begin(), slices_.end(), theta_in,
                                      [](double x, const Slice& s) { return x < s.theta_in; });
  const std::size_t i = static_cast<std::size_t>(upper - slices_.begin()) - 1;
  const double t0 = slices_[i].theta_in, t1 = slices_[i + 1].theta_in;
  const double h = t1 - t0;
  const double s = (theta_in - t0) / h;
  const Rgb y0 = value(i), y1 = value(i + 1);
  if (interpolation == Interpolation::kLinear || n == 2) return y0 + s * (y1 - y0);

  // Slopes at knots i and i+1 need the secants on either side (up to knots i-1 .. i+2).
  const Rgb delta = (y1 - y0) / h;
  Rgb d0, d1;
  if (i > 0) {
    const double hp = t0 - slices_[i - 1].theta_in;
    const Rgb delta_p = (y0 - value(i - 1)) / hp;
    for (int c = 0; c < 3; ++c) d0[c] = InteriorSlope(hp, h, delta_p[c], delta[c]);
  } else {
    const double hn = slices_[i + 2].theta_in - t1;
    const Rgb delta_n = (value(i + 2) - y1) / hn;
    for (int c = 0; c < 3; ++c) d0[c] = EndSlope(h, hn, delta[c], delta_n[c]);
  }
  if (i + 2 < n) {
    const double hn = slices_[i + 2].theta_in - t1;
    const Rgb delta_n = (value(i + 2) - y1) / hn;
    for (int c = 0; c < 3; ++c) d1[c] = InteriorSlope(h, hn, delta[c], delta_n[c]);
  } else {
    const double hp = t0 - slices_[i - 1].theta_in;
    const Rgb delta_p = (y0 - value(i - 1)) / hp;
    for (int c = 0; c < 3; ++c) d1[c] = EndSlope(h, hp, delta[c], delta_p[c]);
  }
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
  const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  const Rgb result = h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1;
  // Monotone on each interval, so only rounding could dip below zero.
  return result.max(0.0);
}

}  // namespace brdfrig::brdf
