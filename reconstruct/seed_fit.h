// The slice rungs of the ladder from measured positions:
//   seed              the seed's model, unchanged: one slice per incidence angle (positions at
//                     the same theta_in within 0.1° pool their samples); a slice whose samples
//                     never reach the lobe's tail takes the median A2 of the slices that do.
//   seed_constrained  the same slices with one diffuse level A2 per channel shared by every
//                     slice, measured from the direction samples farthest from the mirror
//                     direction (theta_h in the top fifth of the observed range, and >= 15°:
//                     where off-specular positions see it), and energy conserved: a slice whose
//                     directional albedo at its theta_in exceeds 1 has its lobe (A1 − A2)
//                     scaled down until it does not.
#pragma once

#include <array>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "brdf/material_file.h"
#include "reconstruct/direction_samples.h"
#include "reconstruct/samples.h"
#include "reconstruct/slice_fit.h"

namespace brdfrig::reconstruct {

// One position's samples as the fits see them.
struct PositionSamples {
  int index = 0;
  BrdfSamples slices;
  DirectionSamples directions;
  std::vector<std::string> warnings;  // carried into the slice diagnostics
};

struct SeedFit {
  brdf::Material material;  // kind seed or seed_constrained, slices + diagnostics
  nlohmann::json slices_from_positions = nlohmann::json::array();
  std::vector<std::string> warnings;
};

// Slice fits made during one ladder run, by the positions whose samples they pool, the
// diffuse level they were held to and whether they carry a covariance. The leave-one-position-
// out folds fit the same slices again and again (a slice depends only on its own positions'
// samples): each is fitted once. Thread-safe; valid only while the positions' samples and the
// other SliceFitOptions stay the same (one ladder run). A fit is deterministic, so the results
// are the same with or without the memo, whatever the order of the fits.
class SliceFitMemo {
 public:
  SliceFit Fit(const std::vector<int>& positions, const BrdfSamples& samples,
               const SliceFitOptions& options, const std::optional<std::array<double, 3>>& a2);

 private:
  using Key = std::tuple<std::vector<int>, bool, bool, std::array<double, 3>>;
  std::mutex mutex_;
  std::map<Key, SliceFit> fits_;
};

// `say`: progress lines (may be empty); `memo`: slice fits to reuse (may be null). Throws
// brdfrig::Error when a slice cannot be fitted.
SeedFit FitSeed(const std::vector<const PositionSamples*>& positions,
                const SliceFitOptions& options, bool constrained,
                const std::function<void(const std::string&)>& say = {},
                SliceFitMemo* memo = nullptr);

}  // namespace brdfrig::reconstruct
