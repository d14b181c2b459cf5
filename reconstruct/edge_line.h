// One straight edge of the paper mask (a side of the cut-out or of the paper's outline), found
// in an HDR image near where the rig's nominal pose projects it.
//
// Profiles across the nominal edge are sampled in log radiance per colour channel, so the
// contrast is a ratio whatever the exposure, of either sign, and visible when only the colour
// differs (a gold sample as bright as the grey paper). Every clear step along a profile is a
// candidate (not only the strongest: a highlight's flank can be steeper than the edge); a
// RANSAC line through the candidates, close to the nominal direction, keeps the ones that are
// collinear, so stretches where the sample matches the paper, highlights touching the edge and
// other clutter only cost points. Sub-pixel positions come from the area under the step.
// A straight feature inside the sample (an iso-angle line of a measured BRDF, a shadow) can hold
// as many steps as the edge itself, so the search returns the few best distinct lines and the
// caller picks among them with the rest of the mask (reconstruct/target.h).
#pragma once

#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::reconstruct {

struct EdgeLineOptions {
  double search_band_m = 0.015;      // half-width of the search band across the edge (metres)
  double corner_skip = 0.08;         // edge fraction near each end not sampled
  double profile_step_px = 2;        // spacing of profiles along the edge
  double min_log_step = 0.2;         // weakest accepted step, |Δ ln(radiance)| over RGB
  int max_candidates = 3;            // steps kept per profile
  double inlier_px = 1.0;            // RANSAC inlier distance
  double max_angle_rad = 0.2;        // line direction vs the nominal edge's direction
  double min_inlier_fraction = 0.2;  // fewest inliers, as a fraction of the profiles sampled
  int max_lines = 3;                 // distinct lines returned, best first
  void Validate() const;
};

// The image in the form the profiles read it: per channel, radiance floored at a small
// fraction of the channel's mean (so black pixels do not dominate the log) and its log.
struct EdgeImage {
  std::array<cv::Mat, 3> linear;  // CV_32F
  std::array<cv::Mat, 3> log;     // CV_32F
};
EdgeImage MakeEdgeImage(const cv::Mat& radiance);

struct EdgeLine {
  cv::Vec4d line;     // unit direction (x, y) and a point (x, y), undistorted pixels
  int inliers = 0;    // profiles with a step on the line
  double rms_px = 0;  // RMS distance of the inliers to the line
};

struct EdgeLines {
  std::vector<EdgeLine> lines;      // most supported first; empty: the edge was not found
  std::vector<cv::Point2d> points;  // every step found (undistorted pixels)
  int profiles = 0;                 // profiles sampled (inside the image)
  int needed = 0;                   // fewest inliers a line needs
};

// Searches for the image of the world segment a→b (plane z = 0): up to max_lines lines with at
// least `needed` inliers each, no two sharing a step. Not finding any (too few collinear steps,
// the edge out of view) is a result, not an error.
EdgeLines FindEdgeLines(const EdgeImage& image, const geometry::Intrinsics& intrinsics,
                        const geometry::CameraPose& nominal, const geometry::Vec3& a,
                        const geometry::Vec3& b, const EdgeLineOptions& options);

// Distance of a point to a line (direction, point).
double LineDistance(const cv::Vec4d& line, const cv::Point2d& p);

// Where two lines (direction, point) cross; false when they are (nearly) parallel.
bool IntersectLines(const cv::Vec4d& a, const cv::Vec4d& b, cv::Point2d* crossing);

}  // namespace brdfrig::reconstruct
