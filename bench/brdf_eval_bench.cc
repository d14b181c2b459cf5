// Slice-model evaluations per second against GGX in the same run (the ratio is what counts on
// a noisy machine). Run: build/release/bench/bench_brdf_eval
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "brdf/analytic.h"
#include "brdf/slice_model.h"
#include "common/angles.h"

namespace brdfrig::brdf {
namespace {

struct Directions {
  std::vector<Vec3> l, v;
};

const Directions& RandomDirections() {
  static const Directions d = [] {
    Directions out;
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 4096; ++i) {
      const double ti = std::acos(u(rng)), to = std::acos(u(rng)), p = 2 * M_PI * u(rng);
      out.l.emplace_back(std::sin(ti), 0, std::cos(ti));
      out.v.emplace_back(std::sin(to) * std::cos(p), std::sin(to) * std::sin(p), std::cos(to));
    }
    return out;
  }();
  return d;
}

SliceModel SixSlices() {
  std::vector<Slice> slices;
  for (int k = 0; k < 6; ++k) {
    Slice s;
    s.theta_in = Radians(15 + 10 * k);
    for (auto& c : s.channel) c = {20.0 + 5 * k, 0.1, 0.03, 0.06};
    slices.push_back(s);
  }
  return SliceModel(slices);
}

template <typename Model>
void EvalLoop(benchmark::State& state, const Model& model) {
  const Directions& d = RandomDirections();
  const Vec3 n = Vec3::UnitZ();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model.Eval(d.l[i], d.v[i], n));
    i = (i + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Ggx(benchmark::State& state) {
  EvalLoop(state, Ggx({Rgb::Constant(0.2), Rgb::Constant(0.04), 0.2}));
}
void BM_SliceModelSpline(benchmark::State& state) { EvalLoop(state, SixSlices()); }
void BM_SliceModelLinear(benchmark::State& state) {
  const SliceModel model = SixSlices();
  const Directions& d = RandomDirections();
  const Vec3 n = Vec3::UnitZ();
  std::size_t i = 0;
  for (auto _ : state) {
    const SliceAngles a = ComputeSliceAngles(d.l[i], d.v[i], n);
    benchmark::DoNotOptimize(model.EvalAngles(a.theta_in, a.theta, Interpolation::kLinear));
    i = (i + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_Ggx);
BENCHMARK(BM_SliceModelSpline);
BENCHMARK(BM_SliceModelLinear);

}  // namespace
}  // namespace brdfrig::brdf

BENCHMARK_MAIN();
