#include "reconstruct/log_loss.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brdfrig::reconstruct {

double WeightedQuantile(std::vector<std::pair<double, double>> value_weight, double q) {
  std::erase_if(value_weight, [](const auto& vw) { return !(vw.second > 0); });
  if (value_weight.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(value_weight.begin(), value_weight.end());
  double total = 0;
  for (const auto& vw : value_weight) total += vw.second;
  const double target = std::clamp(q, 0.0, 1.0) * total;
  double sum = 0;
  for (const auto& [value, weight] : value_weight) {
    sum += weight;
    if (sum >= target) return value;
  }
  return value_weight.back().first;
}

Epsilon LossEpsilon(const std::vector<DirectionSample>& samples, double fraction) {
  Epsilon eps{};
  for (int c = 0; c < 3; ++c) {
    std::vector<std::pair<double, double>> v;
    v.reserve(samples.size());
    double high = 0;
    for (const DirectionSample& s : samples) {
      v.emplace_back(s.f[c] * s.l.z(), LossWeight(s));
      high = std::max(high, s.f[c] * s.l.z());
    }
    const double low = WeightedQuantile(std::move(v), 0.1);
    eps[c] = low > 0 ? fraction * low : std::max(1e-6 * high, 1e-12);
  }
  return eps;
}

double LogLossRms(const brdf::Brdf& model, const std::vector<DirectionSample>& samples,
                  const Epsilon& eps, const std::vector<DirectionSample>& bounds) {
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  double sum = 0, weight = 0;
  const auto add = [&](const DirectionSample& s, bool upper_bound) {
    const double w = LossWeight(s);
    if (!(w > 0)) return;
    const brdf::Rgb f = model.Eval(s.l, s.v, n);
    for (int c = 0; c < 3; ++c) {
      double r = std::log(eps[c] + std::max(f[c], 0.0) * s.l.z()) -
                 std::log(eps[c] + std::max(s.f[c], 0.0) * s.l.z());
      if (upper_bound) r = std::max(r, 0.0);
      sum += w * r * r;
    }
    weight += 3 * w;
  };
  for (const DirectionSample& s : samples) add(s, false);
  for (const DirectionSample& s : bounds) add(s, true);
  return weight > 0 ? std::sqrt(sum / weight) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace brdfrig::reconstruct
