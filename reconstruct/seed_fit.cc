#include "reconstruct/seed_fit.h"
#include "common/angles.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/format.h"
#include "reconstruct/energy.h"

namespace brdfrig::reconstruct {
namespace {

void AppendSamples(BrdfSamples* into, const BrdfSamples& from) {
  const double n_into = static_cast<double>(into->pixels_used);
  const double n_from = static_cast<double>(from.pixels_used);
  into->theta_in =
      (into->theta_in * n_into + from.theta_in * n_from) / std::max(n_into + n_from, 1.0);
  into->theta.insert(into->theta.end(), from.theta.begin(), from.theta.end());
  into->f.insert(into->f.end(), from.f.begin(), from.f.end());
  into->weight.insert(into->weight.end(), from.weight.begin(), from.weight.end());
  into->pixels_used += from.pixels_used;
  into->pixels_invalid += from.pixels_invalid;
  into->theta_in_spread = std::max(into->theta_in_spread, from.theta_in_spread);
  into->angular_pixel_size = std::max(into->angular_pixel_size, from.angular_pixel_size);
}

brdf::SliceDiagnostics Diagnose(const SliceFit& fit, const std::vector<std::string>& extra) {
  brdf::SliceDiagnostics d;
  double residual = 0;
  for (const ChannelFit& c : fit.channel) residual += c.rms_log_residual / 3;
  d.residual = residual;
  d.sample_count = fit.sample_count;
  d.theta_min = fit.theta_min;
  d.theta_max = fit.theta_max;
  d.has_stddev = true;
  for (int c = 0; c < 3; ++c) d.stddev[c] = fit.channel[c].stddev;
  d.warnings = extra;
  d.warnings.insert(d.warnings.end(), fit.warnings.begin(), fit.warnings.end());
  return d;
}

struct SliceInput {
  BrdfSamples samples;
  std::vector<std::string> warnings;
  std::vector<int> positions;
};

// The diffuse level where the samples are farthest from the mirror direction; nullopt when no
// position reaches theta_h 15°.
std::optional<std::array<double, 3>> FarLevel(const std::vector<const PositionSamples*>& positions,
                                              double* reach) {
  double max_h = 0;
  for (const PositionSamples* p : positions) max_h = std::max(max_h, p->directions.theta_h_max);
  *reach = max_h;
  if (max_h < Radians(15)) return std::nullopt;
  const double from = 0.8 * max_h;
  std::array<std::vector<double>, 3> values;
  for (const PositionSamples* p : positions) {
    for (const DirectionSample& s : p->directions.samples) {
      if (HalfAnglesOf(s.l, s.v).theta_h < from) continue;
      for (int c = 0; c < 3; ++c) values[c].push_back(s.f[c]);
    }
  }
  std::array<double, 3> level{};
  for (int c = 0; c < 3; ++c) {
    if (values[c].empty()) return std::nullopt;
    auto mid = values[c].begin() + static_cast<long>(values[c].size() / 2);
    std::nth_element(values[c].begin(), mid, values[c].end());
    level[c] = std::max(*mid, 1e-9);
  }
  return level;
}

}  // namespace

SliceFit SliceFitMemo::Fit(const std::vector<int>& positions, const BrdfSamples& samples,
                           const SliceFitOptions& options,
                           const std::optional<std::array<double, 3>>& a2) {
  const Key key{positions, options.covariance, a2.has_value(),
                a2.value_or(std::array<double, 3>{})};
  {
    std::lock_guard lock(mutex_);
    if (const auto found = fits_.find(key); found != fits_.end()) return found->second;
  }
  // Fitted outside the lock: two threads may fit the same slice at once, with the same result.
  SliceFit fit = FitSlice(samples, options, a2);
  std::lock_guard lock(mutex_);
  fits_.emplace(key, fit);
  return fit;
}

SeedFit FitSeed(const std::vector<const PositionSamples*>& positions,
                const SliceFitOptions& options, bool constrained,
                const std::function<void(const std::string&)>& say, SliceFitMemo* memo) {
  std::vector<const PositionSamples*> sorted = positions;
  std::sort(sorted.begin(), sorted.end(), [](const PositionSamples* a, const PositionSamples* b) {
    return a->slices.theta_in < b->slices.theta_in;
  });
  // One slice per incidence angle: positions at the same theta_in (within 0.1°) pool their
  // samples, so the knots stay strictly increasing.
  std::vector<SliceInput> inputs;
  for (const PositionSamples* p : sorted) {
    if (!inputs.empty() && p->slices.theta_in - inputs.back().samples.theta_in < Radians(0.1)) {
      AppendSamples(&inputs.back().samples, p->slices);
      inputs.back().warnings.push_back("positions pooled: same incidence angle");
    } else {
      inputs.push_back({p->slices, {}, {}});
    }
    for (const std::string& w : p->warnings) inputs.back().warnings.push_back(w);
    inputs.back().positions.push_back(p->index);
  }

  const auto fit_slice = [&](const SliceInput& input,
                             const std::optional<std::array<double, 3>>& a2) {
    return memo ? memo->Fit(input.positions, input.samples, options, a2)
                : FitSlice(input.samples, options, a2);
  };
  SeedFit out;
  std::vector<SliceFit> fits;
  std::optional<std::array<double, 3>> shared_a2;
  if (constrained) {
    double reach = 0;
    shared_a2 = FarLevel(positions, &reach);
    if (!shared_a2) {
      out.warnings.push_back("no position reaches theta_h 15° (farthest " +
                             Fixed(Degrees(reach), 1) +
                             "°): the shared diffuse level A2 is the median of the slices' "
                             "fitted floors, an extrapolation");
    }
  }
  for (const SliceInput& input : inputs) {
    if (say)
      say("fitting the slice at theta_in " + Fixed(Degrees(input.samples.theta_in), 2) + "°");
    fits.push_back(fit_slice(input, shared_a2));
  }
  if (!shared_a2) {
    // A slice whose samples never reach the lobe's tail cannot tell A2: it takes the median A2
    // of the slices that can (the floor is mostly diffuse and varies slowly with theta_in).
    std::array<std::vector<double>, 3> observed_a2;
    for (const SliceFit& fit : fits) {
      if (constrained || fit.a2_observed) {
        for (int c = 0; c < 3; ++c) observed_a2[c].push_back(fit.channel[c].params.a2);
      }
    }
    for (std::size_t i = 0; i < fits.size(); ++i) {
      if (fits[i].a2_observed && !constrained) continue;
      if (observed_a2[0].empty()) {
        fits[i].warnings.push_back("no slice reaches the lobe's tail: A2 is an extrapolation");
        continue;
      }
      std::array<double, 3> shared{};
      for (int c = 0; c < 3; ++c) {
        std::vector<double> v = observed_a2[c];
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        shared[c] = v[v.size() / 2];
      }
      fits[i] = fit_slice(inputs[i], shared);
      fits[i].warnings.push_back(
          "A2 shared across slices: median of the " + std::to_string(observed_a2[0].size()) +
          (constrained ? " slices' fitted floors" : " slices whose samples reach the tail"));
    }
  } else {
    for (SliceFit& fit : fits) {
      // A flat slice (no lobe) comes back as its mean level: the floor is still the shared one.
      for (int c = 0; c < 3; ++c) {
        brdf::LobeParams& p = fit.slice.channel[c];
        p.a2 = (*shared_a2)[c];
        p.a1 = std::max(p.a1, p.a2);
      }
      fit.warnings.push_back("A2 shared by every slice: measured far from the mirror direction");
    }
  }

  brdf::Material& material = out.material;
  material.kind = constrained ? brdf::ModelKind::kSeedConstrained : brdf::ModelKind::kSeed;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    material.slices.push_back(fits[i].slice);
    material.diagnostics.push_back(Diagnose(fits[i], inputs[i].warnings));
    out.slices_from_positions.push_back(
        {{"theta_in", fits[i].slice.theta_in}, {"positions", inputs[i].positions}});
  }
  if (constrained) {
    // Energy: at each knot the spline is that slice, so scaling a slice's lobe bounds the
    // albedo there; the monotone interpolation keeps values between knots within their range.
    for (std::size_t i = 0; i < material.slices.size(); ++i) {
      brdf::Slice& slice = material.slices[i];
      const brdf::SliceModel model(material.slices);
      const brdf::Rgb albedo = HalfVectorAlbedo(model, slice.theta_in);
      double scale = 1;
      for (int c = 0; c < 3; ++c) {
        const double floor = M_PI * slice.channel[c].a2;
        const double lobe = albedo[c] - floor;
        if (albedo[c] > 0.999 && lobe > 0) scale = std::min(scale, (0.999 - floor) / lobe);
      }
      if (scale < 1) {
        scale = std::max(scale, 0.0);
        for (brdf::LobeParams& p : slice.channel) p.a1 = p.a2 + scale * (p.a1 - p.a2);
        material.diagnostics[i].warnings.push_back(
            "energy: directional albedo " + Fixed(albedo.maxCoeff(), 3) +
            " > 1 at this theta_in; the lobe (A1 − A2) scaled by " + Fixed(scale, 4));
      }
    }
  }
  if (constrained) {
    // Between and beyond the knots the albedo can still exceed 1 (the geometry changes with
    // theta_in while a slice stays put): every lobe is scaled by a common factor until the
    // largest albedo over 0°–85° is within bounds.
    for (int round = 0; round < 8; ++round) {
      const AlbedoPeak peak = MaxAlbedo(brdf::SliceModel(material.slices));
      if (peak.albedo <= 0.999) break;
      const double factor = 0.995 * 0.999 / peak.albedo;
      for (brdf::Slice& slice : material.slices) {
        for (brdf::LobeParams& p : slice.channel) {
          p.a1 = p.a2 + factor * (p.a1 - p.a2);
          // A floor alone above the limit (the lobe already gone) comes down too.
          if (round >= 4) {
            p.a2 *= factor;
            p.a1 = std::max(p.a1 * factor, p.a2);
          }
        }
      }
      out.warnings.push_back("energy: albedo " + Fixed(peak.albedo, 3) + " at theta_in " +
                             Fixed(Degrees(peak.theta_in), 0) + "°; every slice's lobe scaled by " +
                             Fixed(factor, 4));
    }
  }
  return out;
}

}  // namespace brdfrig::reconstruct
