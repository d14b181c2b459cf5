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

#include <nlohmann/json.hpp>
#include <string>
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

// `say`: progress lines (may be empty). Throws brdfrig::Error when a slice cannot be fitted.
SeedFit FitSeed(const std::vector<const PositionSamples*>& positions,
                const SliceFitOptions& options, bool constrained,
                const std::function<void(const std::string&)>& say = {});

}  // namespace brdfrig::reconstruct
