// Auto-bracketing: from one metering shot, the bracket of a position. The shortest exposure
// keeps the highlight (the brightest pixel) below `highlight_max`; the longest brings the paper
// around the cut-out and the median of the cut-out itself (both located with the
// nominal geometry) to `paper_level` and `sample_level`, whichever takes longer, but no longer
// than `longest_max_s`.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "acquire/plan.h"
#include "geometry/rig_geometry.h"

namespace brdfrig::acquire {

struct MeteringResult {
  // Set when the metering shot was saturated: meter again at this shorter exposure.
  std::optional<double> remeter_at_s;
  std::vector<double> bracket_s;  // ascending, AutoBracket::count exposures
  double highlight_level = 0;     // brightest pixel of the metering shot
  double paper_level = 0;         // median paper level of the metering shot
  double sample_level = 0;        // median of the cut-out's levels in the metering shot
  // Set when the sample would need a longer exposure than longest_max_s to reach
  // sample_level: the exposure it would need (the bracket stops at longest_max_s).
  std::optional<double> sample_needs_s;
};

// `levels`: the metering shot as fractions of full scale (FrameCheck's `levels`).
MeteringResult ChooseBracket(const cv::Mat& levels, double metering_exposure_s,
                             const geometry::RigGeometry& geometry,
                             const geometry::AxisPositions& axes, const AutoBracket& settings);

}  // namespace brdfrig::acquire
