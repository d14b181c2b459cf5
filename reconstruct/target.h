// Finding the paper mask's cut-out in an HDR image and the camera pose from its corners.
//
// The search starts from the cut-out as the rig's nominal pose projects it: each of the four
// edges yields up to lines_per_edge robust lines through the steps found on profiles across it
// (reconstruct/edge_line.h: log radiance per colour channel, either sign, several candidates per
// profile, RANSAC). A straight feature inside a sample (an iso-angle line of a measured BRDF)
// can hold as many steps as the edge, so the sides are chosen together: every combination of
// the edges' lines gives a pose (fitted to the lines, reconstruct/line_pose.h) and the one whose
// posed rectangle explains the most steps of all four edges wins, taken when it keeps each side
// on enough of its own steps. The corners are then the chosen lines' intersections, so a corner
// hidden from view is still found. Where a side shows too little contrast along its whole
// length (a sample as bright and as coloured as the paper there) or no combination forms the
// cut-out, the paper's outline joins in, any side may be left out, and the cut-out's corners
// are the projections of the best line-fitted pose.
#pragma once

#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::reconstruct {

struct TargetOptions {
  double search_band = 0.15;       // half-width of the search band, fraction of the cut-out's size
  double corner_skip = 0.08;       // edge fraction near each corner not sampled (shadows, blur)
  double profile_step_px = 2;      // spacing of profiles along an edge
  double min_log_step = 0.2;       // weakest accepted step, |Δ ln(radiance)| over RGB
  double min_edge_fraction = 0.2;  // fewest collinear steps per edge, fraction of its profiles
  bool use_paper_outline = true;   // the paper's outer edges help when a cut-out edge is weak
  int lines_per_edge = 3;          // candidate lines kept per edge for the joint choice
  double max_reprojection_px = 2.0;  // a pose worse than this is refused
  // On a marker mask: fewer markers found than this and the pose comes from the cut-out's
  // corners instead (four markers are sixteen corners around the cut-out).
  int min_markers = 4;
  // A measured camera this far from the rig's nominal one is used, with a warning: either the
  // rig file is off or the edges were found on badly exposed photos.
  double warn_camera_offset_m = 0.02;
  void Validate() const;
};

// Corners in (undistorted) pixel coordinates in the order of the world corners
// (-w/2,-h/2), (+w/2,-h/2), (+w/2,+h/2), (-w/2,+h/2) on the plane z = 0.
struct TargetCorners {
  std::array<cv::Point2d, 4> corners;
  std::array<int, 4> edge_points{};  // accepted profiles per edge (0: the edge was not found)
  double line_rms_px = 0;            // RMS distance of edge points to their lines
  int cutout_edges_found = 0;        // 4: corners are the edges' crossings
  int paper_edges_found = 0;         // searched only when a cut-out edge was not found
};

struct PoseEstimate {
  geometry::CameraPose pose;
  double reprojection_rms_px = 0;
  double distance_m = 0;              // camera centre to the cut-out's centre
  double nominal_disagreement_m = 0;  // |measured centre - nominal centre|
};

// Throws brdfrig::Error ("target not found: ...") when the edges found do not fix the corners.
TargetCorners FindCutoutCorners(const cv::Mat& radiance, const cv::Mat& valid,
                                const geometry::Intrinsics& intrinsics,
                                const geometry::CameraPose& nominal,
                                const geometry::TargetGeometry& target,
                                const TargetOptions& options);

// Planar PnP (IPPE) refined by Levenberg–Marquardt on the four corners. Throws brdfrig::Error for
// an implausible pose (reprojection error, camera below the sample, far from nominal).
PoseEstimate EstimatePose(const TargetCorners& corners, const geometry::Intrinsics& intrinsics,
                          const geometry::TargetGeometry& target,
                          const geometry::CameraPose& nominal, const TargetOptions& options);

// The same for any points of the sample plane (z = 0) and their undistorted pixels, at least
// four; `what` names them in errors ("the mask's marker corners").
PoseEstimate PoseFromPlanePoints(const std::vector<cv::Point3d>& object,
                                 const std::vector<cv::Point2d>& image,
                                 const geometry::Intrinsics& intrinsics,
                                 const geometry::CameraPose& nominal, const TargetOptions& options,
                                 const std::string& what);

// Intrinsics with the distortion removed (what undistorted pixel coordinates refer to).
cv::Matx33d CameraMatrix(const geometry::Intrinsics& intrinsics);
cv::Point2d UndistortPixel(const geometry::Intrinsics& intrinsics, const cv::Point2d& pixel);

}  // namespace brdfrig::reconstruct
