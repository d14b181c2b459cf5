// Auto-bracketing: from one metering shot, the bracket of a position. The shortest exposure
// keeps the highlight (the brightest pixel) below `highlight_max`; the longest brings the paper
// around the cut-out (located with the nominal geometry) to `paper_level`.
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
};

// `levels`: the metering shot as fractions of full scale (FrameCheck's `levels`).
MeteringResult ChooseBracket(const cv::Mat& levels, double metering_exposure_s,
                             const geometry::RigGeometry& geometry,
                             const geometry::AxisPositions& axes, const AutoBracket& settings);

}  // namespace brdfrig::acquire
