#include "reconstruct/target.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "common/error.h"
#include "common/option_check.h"
#include "reconstruct/edge_line.h"

namespace brdfrig::reconstruct {
namespace {

std::array<geometry::Vec3, 4> Rectangle(double width, double height) {
  const double w = width / 2, h = height / 2;
  return {geometry::Vec3(-w, -h, 0), geometry::Vec3(w, -h, 0), geometry::Vec3(w, h, 0),
          geometry::Vec3(-w, h, 0)};
}

std::array<geometry::Vec3, 4> WorldCorners(const geometry::TargetGeometry& target) {
  return Rectangle(target.cutout_width, target.cutout_height);
}

// An edge found in the image with the world line it is the image of: edge k of a rectangle
// from Rectangle() lies on y = const for even k, x = const for odd k.
struct WorldLine {
  bool horizontal;  // y = value
  double value;
  cv::Vec4d image;
};

// Pose from whatever edges were found, cut-out and paper outline alike: every crossing of an
// x = const line with a y = const line is a known point of the plane; a planar PnP on them gives
// the pose, and the cut-out's corners are its projections. Used when a side of the cut-out shows
// too little contrast (the sample as bright and as coloured as the paper there).
bool CornersFromLines(const std::vector<WorldLine>& lines, const geometry::Intrinsics& intrinsics,
                      const geometry::TargetGeometry& target, std::array<cv::Point2d, 4>* corners) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  int horizontal = 0, vertical = 0;
  for (const WorldLine& l : lines) (l.horizontal ? horizontal : vertical) += 1;
  if (horizontal < 2 || vertical < 2) return false;
  for (const WorldLine& h : lines) {
    if (!h.horizontal) continue;
    for (const WorldLine& v : lines) {
      cv::Point2d crossing;
      if (v.horizontal || !IntersectLines(h.image, v.image, &crossing)) continue;
      object.emplace_back(v.value, h.value, 0);
      image.push_back(crossing);
    }
  }
  if (object.size() < 4) return false;
  const cv::Mat k(CameraMatrix(intrinsics));
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(object, image, k, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE)) {
    return false;
  }
  cv::solvePnPRefineLM(object, image, k, cv::noArray(), rvec, tvec);
  std::vector<cv::Point3d> world;
  for (const geometry::Vec3& w : WorldCorners(target)) world.emplace_back(w.x(), w.y(), w.z());
  std::vector<cv::Point2d> projected;
  cv::projectPoints(world, rvec, tvec, k, cv::noArray(), projected);
  std::copy(projected.begin(), projected.end(), corners->begin());
  return true;
}

}  // namespace

void TargetOptions::Validate() const {
  CheckOption(search_band > 0 && search_band < 0.5, "TargetOptions.search_band", search_band,
              "in (0, 0.5)");
  CheckOption(corner_skip >= 0 && corner_skip < 0.4, "TargetOptions.corner_skip", corner_skip,
              "in [0, 0.4)");
  CheckOption(profile_step_px > 0, "TargetOptions.profile_step_px", profile_step_px, "> 0");
  CheckOption(warn_camera_offset_m > 0, "TargetOptions.warn_camera_offset_m", warn_camera_offset_m,
              "> 0");
  CheckOption(min_log_step > 0, "TargetOptions.min_log_step", min_log_step, "> 0");
  CheckOption(min_edge_fraction > 0 && min_edge_fraction <= 1, "TargetOptions.min_edge_fraction",
              min_edge_fraction, "in (0, 1]");
  CheckOption(max_reprojection_px > 0, "TargetOptions.max_reprojection_px", max_reprojection_px,
              "> 0");
}

cv::Matx33d CameraMatrix(const geometry::Intrinsics& k) {
  return {k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1};
}

cv::Point2d UndistortPixel(const geometry::Intrinsics& k, const cv::Point2d& pixel) {
  if (k.k1 == 0 && k.k2 == 0) return pixel;
  // The ray through the pixel, projected again without distortion.
  const geometry::Vec3 ray =
      geometry::PixelRayInWorld(k, geometry::CameraPose{}, {pixel.x, pixel.y});
  return {k.fx * ray.x() / ray.z() + k.cx, k.fy * ray.y() / ray.z() + k.cy};
}

TargetCorners FindCutoutCorners(const cv::Mat& radiance, const cv::Mat& valid,
                                const geometry::Intrinsics& intrinsics,
                                const geometry::CameraPose& nominal,
                                const geometry::TargetGeometry& target,
                                const TargetOptions& options) {
  options.Validate();
  (void)valid;  // clipped pixels keep their lower bound, which still marks an edge
  const EdgeImage image = MakeEdgeImage(radiance);
  EdgeLineOptions edge_options;
  edge_options.search_band_m =
      options.search_band * std::min(target.cutout_width, target.cutout_height);
  edge_options.corner_skip = options.corner_skip;
  edge_options.profile_step_px = options.profile_step_px;
  edge_options.min_log_step = options.min_log_step;
  edge_options.min_inlier_fraction = options.min_edge_fraction;

  TargetCorners result;
  std::vector<WorldLine> lines;
  std::string missing;
  const auto search = [&](const std::array<geometry::Vec3, 4>& rectangle, int e) {
    const EdgeLine found = FindEdgeLine(image, intrinsics, nominal, rectangle[e],
                                        rectangle[(e + 1) % 4], edge_options);
    if (found.found) {
      lines.push_back({e % 2 == 0, e % 2 == 0 ? rectangle[e].y() : rectangle[e].x(), found.line});
    }
    return found;
  };
  double rms_sum = 0;
  for (int e = 0; e < 4; ++e) {
    const EdgeLine found = search(WorldCorners(target), e);
    result.edge_points[e] = found.inliers;
    if (found.found) {
      ++result.cutout_edges_found;
      rms_sum += found.rms_px * found.rms_px;
    } else {
      missing += (missing.empty() ? "" : "; ") + std::string("edge ") + std::to_string(e) + ": " +
                 std::to_string(found.candidates) + " steps on " + std::to_string(found.profiles) +
                 " profiles, none enough in a line";
    }
  }
  if (result.cutout_edges_found == 4) {
    // Corner k is where edge k-1 (arriving) meets edge k (leaving).
    for (int k = 0; k < 4; ++k) {
      if (!IntersectLines(lines[(k + 3) % 4].image, lines[k].image, &result.corners[k])) {
        throw Error("target not found: two edges of the cut-out are parallel");
      }
    }
    result.line_rms_px = std::sqrt(rms_sum / 4);
    return result;
  }
  if (options.use_paper_outline) {
    const auto paper = Rectangle(target.paper_width, target.paper_height);
    for (int e = 0; e < 4; ++e) result.paper_edges_found += search(paper, e).found ? 1 : 0;
    if (CornersFromLines(lines, intrinsics, target, &result.corners)) {
      result.line_rms_px =
          result.cutout_edges_found > 0 ? std::sqrt(rms_sum / result.cutout_edges_found) : 0;
      return result;
    }
  }
  throw Error("target not found: " + std::to_string(result.cutout_edges_found) +
              " of the cut-out's 4 edges and " + std::to_string(result.paper_edges_found) +
              " of the paper's found near where the rig's nominal pose puts them (" + missing +
              "); is the mask in view, the rig geometry right, the exposure sensible?");
}

PoseEstimate EstimatePose(const TargetCorners& corners, const geometry::Intrinsics& intrinsics,
                          const geometry::TargetGeometry& target,
                          const geometry::CameraPose& nominal, const TargetOptions& options) {
  std::vector<cv::Point3d> object;
  for (const geometry::Vec3& w : WorldCorners(target)) object.emplace_back(w.x(), w.y(), w.z());
  std::vector<cv::Point2d> image(corners.corners.begin(), corners.corners.end());
  const cv::Mat k(CameraMatrix(intrinsics));
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(object, image, k, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE)) {
    throw Error("pose not found: the cut-out's corners admit no planar pose");
  }
  cv::solvePnPRefineLM(object, image, k, cv::noArray(), rvec, tvec);
  std::vector<cv::Point2d> reprojected;
  cv::projectPoints(object, rvec, tvec, k, cv::noArray(), reprojected);
  double sum_sq = 0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const cv::Point2d d = reprojected[i] - image[i];
    sum_sq += d.dot(d);
  }
  PoseEstimate estimate;
  estimate.reprojection_rms_px = std::sqrt(sum_sq / 4);
  cv::Matx33d r;
  cv::Rodrigues(rvec, r);
  Eigen::Matrix3d rotation;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) rotation(i, j) = r(i, j);
  }
  estimate.pose.camera_from_world.linear() = rotation;
  estimate.pose.camera_from_world.translation() =
      geometry::Vec3(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  const geometry::Vec3 centre = estimate.pose.CenterInWorld();
  const geometry::Vec3 nominal_centre = nominal.CenterInWorld();
  estimate.distance_m = centre.norm();
  estimate.nominal_disagreement_m = (centre - nominal_centre).norm();
  if (estimate.reprojection_rms_px > options.max_reprojection_px) {
    throw Error("implausible pose: the cut-out's corners reproject with " +
                std::to_string(estimate.reprojection_rms_px) + " px RMS error (limit " +
                std::to_string(options.max_reprojection_px) + " px)");
  }
  if (centre.z() <= 0) throw Error("implausible pose: the camera would be below the sample");
  const double nominal_distance = nominal_centre.norm();
  if (estimate.distance_m > 2 * nominal_distance || estimate.distance_m < 0.5 * nominal_distance) {
    throw Error("implausible pose: camera " + std::to_string(estimate.distance_m) +
                " m from the sample, the rig says " + std::to_string(nominal_distance) + " m");
  }
  return estimate;
}

}  // namespace brdfrig::reconstruct
