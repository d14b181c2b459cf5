// The camera pose from straight edges of a plane: lines found in the image that are the images
// of known lines on the world plane z = 0 (the cut-out's sides, the paper's outline).
//
// Crossings of the lines would give a point PnP, but only where an x = const and a y = const
// line are both found; at grazing views one whole direction can be blind (a side of the cut-out
// as bright as the paper, the paper's near edge out of view) while four lines of the other
// direction and one of the first still fix the pose. So the pose is fitted to the lines
// themselves: Levenberg–Marquardt on the distances of two points of each image line (near the
// segment's ends) to the posed world line, from a starting pose (the rig's nominal one).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "geometry/rig_geometry.h"

namespace brdfrig::reconstruct {

struct PlaneLine {
  geometry::Vec3 a, b;  // a segment of the world line (z = 0)
  cv::Vec4d image;      // its image: unit direction (x, y) and a point (x, y), undistorted pixels
};

struct LinePose {
  cv::Vec3d rvec, tvec;  // OpenCV's camera_from_world (Rodrigues vector, translation)
  double rms_px = 0;     // RMS distance of the lines' points to the posed world lines
};

// False when the lines do not fix a pose (fewer than four, or all of one direction) or the fit
// does not converge to a camera in front of the plane.
bool PoseFromPlaneLines(const std::vector<PlaneLine>& lines, const cv::Matx33d& k,
                        const geometry::CameraPose& start, LinePose* pose);

// OpenCV's pose vectors as a CameraPose.
geometry::CameraPose ToCameraPose(const cv::Vec3d& rvec, const cv::Vec3d& tvec);

}  // namespace brdfrig::reconstruct
