// The camera pose from the marker mask (docs/calibration.md, "Pose from the marker mask"): the
// mask's ArUco markers around the cut-out give dozens of corners at known places on the sample
// plane, so the pose does not hang on the cut-out's four corners — which a mirror-like sample,
// or a highlight touching an edge, can hide or move. The cut-out stays the sample's boundary.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "geometry/rig_geometry.h"
#include "reconstruct/target.h"

namespace brdfrig::reconstruct {

// The mask's marker corners found in one merged photo, matched to where they are printed.
struct MarkerCorners {
  std::vector<cv::Point3d> world;  // on the sample plane (z = 0), metres
  std::vector<cv::Point2d> image;  // undistorted pixel coordinates
  int markers = 0;                 // markers found (4 corners each)
};

// Finds the rig's marker mask (target.markers) in the merged radiance. Only ids that the mask
// prints count; pixels marked invalid are painted white first so clipped or masked areas cannot
// form markers. Empty when the rig describes no marker mask.
MarkerCorners FindMaskMarkers(const cv::Mat& radiance, const cv::Mat& valid,
                              const geometry::Intrinsics& intrinsics,
                              const geometry::TargetGeometry& target);

}  // namespace brdfrig::reconstruct
