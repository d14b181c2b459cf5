// Finding the paper mask's cut-out in an HDR image and the camera pose from its corners.
//
// The search starts from the cut-out as the rig's nominal pose projects it: along each of the
// four edges, profiles across the edge are sampled in log luminance (so the contrast is a ratio,
// whatever the exposure) and the strongest step within the search band gives an edge point,
// refined to sub-pixel by a parabola through the gradient peak. Profiles without a clear step
// (the sample as bright as the paper there, an occluding object) are dropped; the rest give a
// robust line per edge, and the corners are the lines' intersections — so a corner hidden from
// view is still found. The sample may be brighter (a highlight) or darker than the paper: the
// step's sign is not assumed.
#pragma once

#include <array>
#include <opencv2/core.hpp>
#include <string>

#include "geometry/rig_geometry.h"

namespace brdfrig::reconstruct {

struct TargetOptions {
  double search_band = 0.15;        // half-width of the search band, fraction of the cut-out's size
  double corner_skip = 0.08;        // edge fraction near each corner not sampled (shadows, blur)
  double profile_step_px = 2;       // spacing of profiles along an edge
  double min_log_step = 0.2;        // weakest accepted step in ln(luminance) across an edge
  double min_edge_fraction = 0.25;  // fewest accepted profiles per edge, as a fraction
  double max_reprojection_px = 2.0;  // a pose worse than this is refused
  // A measured camera this far from the rig's nominal one is used, with a warning: either the
  // rig file is off or the edges were found on badly exposed photos.
  double warn_camera_offset_m = 0.02;
  void Validate() const;
};

// Corners in (undistorted) pixel coordinates in the order of the world corners
// (-w/2,-h/2), (+w/2,-h/2), (+w/2,+h/2), (-w/2,+h/2) on the plane z = 0.
struct TargetCorners {
  std::array<cv::Point2d, 4> corners;
  std::array<int, 4> edge_points{};  // accepted profiles per edge
  double line_rms_px = 0;            // RMS distance of edge points to their lines
};

struct PoseEstimate {
  geometry::CameraPose pose;
  double reprojection_rms_px = 0;
  double distance_m = 0;              // camera centre to the cut-out's centre
  double nominal_disagreement_m = 0;  // |measured centre - nominal centre|
};

// Throws brdfrig::Error ("target not found: ...") when an edge has too few clear profiles.
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

// Intrinsics with the distortion removed (what undistorted pixel coordinates refer to).
cv::Matx33d CameraMatrix(const geometry::Intrinsics& intrinsics);
cv::Point2d UndistortPixel(const geometry::Intrinsics& intrinsics, const cv::Point2d& pixel);

}  // namespace brdfrig::reconstruct
