// `brdfrig target print`: the ChArUco board and the marker mask as PDF and SVG at exact size,
// and targets.json with their geometry (every marker corner of the mask in mask coordinates).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "calibrate/charuco_spec.h"
#include "calibrate/marker_mask.h"

namespace brdfrig::calibrate {

struct PrintTargetsOptions {
  std::filesystem::path output_dir;
  CharucoSpec board;
  MarkerMaskSpec mask;    // cut-out and paper from the rig's target (MarkerMaskSpec::ForTarget)
  void Validate() const;  // throws OptionsError
};

struct PrintTargetsSummary {
  std::vector<std::filesystem::path> files;
  int board_corners = 0, mask_markers = 0;
  std::string ToString() const;
};

PrintTargetsSummary PrintTargets(const PrintTargetsOptions& options);

}  // namespace brdfrig::calibrate
