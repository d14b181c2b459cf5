#include "reconstruct/log_loss.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brdfrig::reconstruct {

Epsilon LossEpsilon(const std::vector<DirectionSample>& samples, double fraction) {
  Epsilon eps{};
  for (int c = 0; c < 3; ++c) {
    std::vector<double> v;
    v.reserve(samples.size());
    for (const DirectionSample& s : samples) v.push_back(s.f[c] * s.l.z());
    if (v.empty()) {
      eps[c] = 1e-12;
      continue;
    }
    const auto p10 = v.begin() + static_cast<long>(v.size() / 10);
    std::nth_element(v.begin(), p10, v.end());
    const double low = *p10;
    const double high = *std::max_element(v.begin(), v.end());
    eps[c] = low > 0 ? fraction * low : std::max(1e-6 * high, 1e-12);
  }
  return eps;
}

double LogLossRms(const brdf::Brdf& model, const std::vector<DirectionSample>& samples,
                  const Epsilon& eps) {
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  double sum = 0, weight = 0;
  for (const DirectionSample& s : samples) {
    const double w = LossWeight(s);
    if (!(w > 0)) continue;
    const brdf::Rgb f = model.Eval(s.l, s.v, n);
    for (int c = 0; c < 3; ++c) {
      const double r = std::log(eps[c] + std::max(f[c], 0.0) * s.l.z()) -
                       std::log(eps[c] + std::max(s.f[c], 0.0) * s.l.z());
      sum += w * r * r;
    }
    weight += 3 * w;
  }
  return weight > 0 ? std::sqrt(sum / weight) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace brdfrig::reconstruct
