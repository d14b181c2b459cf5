// The plan designer: chooses capture positions for a rig by maximising a weighted coverage of
// the (θh, θd) domain (coverage.h), under the rig's constraints. No angle is hard-coded: the
// positions follow from the rig (axes, limits, distances, cut-out, camera) and the objective.
//
// Objective (a weighted set cover, so greedy selection is within 1 − 1/e of the optimum and a
// swap search improves on it): the union of the chosen positions' elements, each counted once:
//   - every cell of the (θh, θd) grid, weight `cell_weight` (area on the sqrt-warped θh axis
//     already favours the specular peak);
//   - every θh bin seen at any θd, weight `theta_h_weight`: a shared microfacet distribution
//     D(θh) needs the whole θh axis once — peak, flanks, tail and the diffuse floor;
//   - every θd bin seen near the peak (θh ≤ `peak_theta_h_deg`), weight `theta_d_weight`: the
//     Fresnel curve F(θd) is measured where the specular term dominates;
//   both marginals are smooth, so a seen bin also counts its neighbours within
//   `theta_h_reach_bins` / `theta_d_reach_bins` (this spreads the photos along each axis);
//   - one photo near retro-reflection (θd ≤ `retro_theta_d_deg` somewhere on the cut-out) and
//     one with grazing light (θi ≥ `grazing_theta_in_deg` at the centre), `requirement_weight`
//     each: the back-scatter and grazing-Fresnel ends a sparse plan otherwise misses.
// Constraints per position: axes within limits; the cut-out's four corners project inside the
// image (nominal intrinsics, with a margin); camera within `max_view_deg` of the normal (a
// grazing view leaves few pixels and a poor pose); light within `max_light_deg`; camera and
// light at least `min_separation_deg` apart (the light cannot sit in front of the lens).
//
// Search: a grid of candidates over every axis (`step_deg`, coarsened until the grid has at
// most `max_candidates`), greedy selection, then up to `refine_passes` passes that retry each
// chosen position against every candidate and against its neighbours at half and quarter
// steps (a local continuous refinement). Validation positions, when asked for, are chosen
// after the fitted ones by the same gain: the regions the fit does not see.
#pragma once

#include <string>
#include <vector>

#include "coverage/coverage.h"
#include "prior/measured_prior.h"

namespace brdfrig::coverage {

struct DesignOptions {
  // "prior": positions chosen by the expected reconstruction error under the shipped measured
  // prior (prior_objective.h; the coverage weights below then only choose validation
  // positions); "coverage": by the weighted coverage above.
  std::string objective = "prior";
  int prior_components = 32;                    // leading components the prior objective uses
  const prior::MeasuredPrior* prior = nullptr;  // nullptr: the shipped prior (studies pass one)
  int count = 6;                                // fitted positions, 1..24
  int validation = 0;                           // extra validation positions, 0..24
  double step_deg = 10;
  int max_candidates = 50000;  // 100 .. 1000000
  int refine_passes = 4;       // 0 .. 20
  double min_separation_deg = 10;
  double max_view_deg = 70;  // beyond, the cut-out is a thin sliver: few pixels, a poor pose
  double max_light_deg = 85;
  double image_margin_px = 10;
  double peak_theta_h_deg = 8;
  double retro_theta_d_deg = 15;
  double grazing_theta_in_deg = 70;
  double cell_weight = 1;
  double theta_h_weight = 8;
  double theta_d_weight = 3;
  double requirement_weight = 30;
  // How far (in bins) one sample constrains the smooth θh and θd marginals.
  int theta_h_reach_bins = 1;
  int theta_d_reach_bins = 2;
  // Grid of the search (fewer cut-out points than the final map, for speed); the final
  // coverage is recomputed with `report_grid`.
  GridOptions search_grid{32, 32, 9};  // 81 points: 0.3 s for the default rig
  GridOptions report_grid;
  void Validate() const;  // throws OptionsError naming field, value and rule
};

// What a geometry change would do to one photo's coverage.
struct WidenHint {
  std::string change;  // e.g. "cut-out 150 × 150 mm"
  int cells = 0;       // cells with the change (0 when it does not fit the image)
  bool fits = true;    // the cut-out's corners are still inside the image
};

struct DesignedPosition {
  PositionCoverage coverage;  // axes, role, ranges, cells (report grid)
  double gain = 0;            // coverage objective added when chosen (in the final order)
  // Prior objective: the expected RMS error per table node after this position (in the final
  // order) and how much this position lowered it.
  double expected_rms_after = 0, prior_gain = 0;
  std::string reason;  // one line: why this position (what it contributes)
  std::vector<WidenHint> widen;
};

struct PlanDesign {
  DesignOptions options;
  std::vector<DesignedPosition> positions;  // fitted first, then validation
  double score = 0, max_score = 0;          // objective of the fitted positions, and its maximum
  double covered_fraction = 0;              // cells of the fitted positions (report grid)
  int candidates = 0;                       // valid candidates searched
  double step_deg = 0;                      // the candidate step actually used
  bool has_retro = false, has_grazing = false;
  std::string objective;  // "prior" or "coverage"
  // Prior objective: RMS error of ln(f c + ε) per table node from the prior alone, expected
  // with the fitted positions, and measured leave-one-material-out over the training set.
  std::string prior_name;
  double prior_only_rms = 0, expected_rms = 0, leave_one_out_rms = 0;
  std::vector<geometry::AxisPositions> Positions() const;
  std::vector<bool> Validation() const;
  std::string ToString() const;  // the explanation `plan check` prints
};

// Throws brdfrig::Error when the rig allows fewer valid positions than asked for.
PlanDesign DesignPlan(const geometry::RigGeometry& rig, const DesignOptions& options);

// The constraint check on its own (for tests and plan check): "" when the position is
// acceptable, otherwise what is wrong.
std::string CheckDesignConstraints(const geometry::RigGeometry& rig,
                                   const geometry::AxisPositions& axes,
                                   const DesignOptions& options);

}  // namespace brdfrig::coverage
