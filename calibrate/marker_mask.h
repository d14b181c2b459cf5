// The marker mask: the paper mask with its rectangular cut-out (the sample's boundary) and a
// ring of ArUco markers around the cut-out, so that the pose can come from dozens of marker
// corners rather than the cut-out's four. The one description of where every marker corner is,
// for printing (`brdfrig target print`) and for whoever detects the markers.
//
// Mask coordinates are the world's sample plane (z = 0): the cut-out centred at the origin,
// x along world +x, y along world +y, metres. The sheet is printed with world +y at the top of
// the page, so a marker's corners in ArUco's order (top-left, top-right, bottom-right,
// bottom-left as printed) run clockwise seen from above.
#pragma once

#include <Eigen/Core>
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::calibrate {

struct MarkerMaskSpec {
  double cutout_width_m = 0.1, cutout_height_m = 0.1;  // the cut-out (sample's boundary)
  double paper_width_m = 0.3, paper_height_m = 0.3;    // the sheet (= the printed page)
  double marker_m = 0.02;                              // side of a marker (black border included)
  double gap_m = 0.01;      // from the cut-out's edge to the ring of markers
  double spacing_m = 0.01;  // at least this much white between neighbouring markers
  std::string dictionary = "DICT_4X4_100";
  int first_id = 0;  // markers take ids first_id, first_id + 1, ... around the ring

  // The cut-out and paper of a rig's target, with its ring of markers (the defaults when the
  // target describes none).
  static MarkerMaskSpec ForTarget(const geometry::TargetGeometry& target);

  // Throws OptionsError naming the field: the ring must fit inside the paper with room for the
  // scale bar, and the dictionary must hold every id.
  void Validate() const;
  nlohmann::json ToJson() const;
};

struct MaskMarker {
  int id = 0;
  // Corners in ArUco's order (top-left, top-right, bottom-right, bottom-left as printed), in mask
  // coordinates (metres, world x and y on the sample plane).
  std::array<Eigen::Vector2d, 4> corners;
};

// Every marker of the ring, top row left to right, then the right column downwards, the bottom
// row right to left and the left column upwards.
std::vector<MaskMarker> MaskMarkers(const MarkerMaskSpec& spec);

}  // namespace brdfrig::calibrate
