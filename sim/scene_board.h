// A printed ChArUco board held in the simulated world (a scene's `board:` section), so lens
// calibration runs end to end on simulated photos through the same code as on hardware. The
// board is the sheet `brdfrig target print` writes (calibrate/), rasterized finely and seen as a
// Lambertian print: paper where there is no ink, ink where there is. It casts no shadow.
//
//   board:
//     target: {squares: [11, 8], square_mm: 20, marker_mm: 15, dictionary: DICT_5X5_100,
//              page_mm: [297, 210]}                (calibrate::CharucoSpec; all optional)
//     albedo: {paper: 0.85, ink: 0.04}
//     exposure_s: 0.0333                           (what `brdfrig simulate` photographs it at)
//     poses:                                       (one photo per pose)
//       - {center: [0, 0, 0.05], rotation_deg: [20, -10, 5]}
//
// A pose puts the page's centre at `center` (world, metres). At rotation 0 the page lies face
// up (printed side towards +z) with its top edge towards world +y, as a camera above the rig
// at rest reads it; the rotations then turn it about world x, y and z, in that order, about its
// centre.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "calibrate/charuco_spec.h"
#include "common/yaml_reader.h"
#include "sim/sheet_print.h"

namespace brdfrig::sim {

struct SceneBoard {
  calibrate::CharucoSpec spec;
  double paper_albedo = 0.85, ink_albedo = 0.04;
  double exposure_s = 1.0 / 30;
  // world_from_page per pose: page coordinates are metres from the page's top-left, x along
  // the page, y down it, z into the sheet (calibrate/'s board coordinates, shifted by
  // spec.OriginOnPage()).
  std::vector<Eigen::Isometry3d> world_from_page;
};

SceneBoard ParseSceneBoard(const YamlNode& node);

// The board's page as the simulator sees it.
SheetPrint PrintOfBoard(const SceneBoard& board);

}  // namespace brdfrig::sim
