// Noise-free BRDF samples at the directions a plan's photos see: 25 x 25 points over the
// cut-out per position from the rig's nominal geometry (as the coverage map sees them), f from
// the truth. What a plan can give a fit without the capture (bench_model_ceiling's "designed"
// data, bench_prior_study).
#pragma once

#include <vector>

#include "brdf/brdf.h"
#include "geometry/rig_geometry.h"
#include "reconstruct/seed_fit.h"

namespace brdfrig::bench {

inline reconstruct::DirectionSample SampleOf(const brdf::Brdf& truth, const brdf::Vec3& l,
                                             const brdf::Vec3& v) {
  reconstruct::DirectionSample s;
  s.l = l;
  s.v = v;
  const brdf::Rgb f = truth.Eval(l, v, brdf::Vec3::UnitZ());
  for (int c = 0; c < 3; ++c) s.f[c] = f[c];
  return s;
}

inline std::vector<reconstruct::PositionSamples> PlanSamples(
    const brdf::Brdf& truth, const geometry::RigGeometry& rig,
    const std::vector<geometry::AxisPositions>& plan) {
  std::vector<reconstruct::PositionSamples> out;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    reconstruct::PositionSamples p;
    p.index = static_cast<int>(i);
    const geometry::Vec3 camera = rig.CameraAt(plan[i]).CenterInWorld();
    const geometry::Vec3 light = rig.LightAt(plan[i]);
    const int n = 25;
    for (int iy = 0; iy < n; ++iy) {
      for (int ix = 0; ix < n; ++ix) {
        const geometry::Vec3 x((ix / (n - 1.0) - 0.5) * rig.target.cutout_width,
                               (iy / (n - 1.0) - 0.5) * rig.target.cutout_height, 0);
        p.directions.samples.push_back(
            SampleOf(truth, (light - x).normalized(), (camera - x).normalized()));
      }
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace brdfrig::bench
