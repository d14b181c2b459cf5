#include "reconstruct/target.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "common/error.h"
#include "common/option_check.h"
#include "reconstruct/edge_line.h"
#include "reconstruct/line_pose.h"

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

// One straight edge of the mask searched for in the image: the world line it lies on (y = value
// for a horizontal edge, x = value otherwise) and the lines found near its nominal image.
struct Slot {
  bool horizontal;
  double value;
  geometry::Vec3 a, b;  // the segment's ends
  EdgeLines found;
};

// A choice of one found line per slot (or none, kChooseNone), the pose the chosen lines give, and
// how well that pose explains every slot's steps.
constexpr int kChooseNone = -1;
struct Choice {
  std::vector<int> pick;
  cv::Mat rvec, tvec;
  std::size_t support = 0;  // steps of all slots within inlier_px of the posed mask
  std::vector<std::size_t> per_slot;
  double line_rms_px = 0;  // the chosen lines' distance to the posed mask
};

// The pose the chosen lines give (reconstruct/line_pose.h), from the rig's nominal pose.
bool PoseFromLines(const std::vector<Slot>& slots, const cv::Matx33d& k,
                   const geometry::CameraPose& nominal, Choice* choice) {
  std::vector<PlaneLine> lines;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (choice->pick[i] == kChooseNone) continue;
    lines.push_back({slots[i].a, slots[i].b, slots[i].found.lines[choice->pick[i]].line});
  }
  LinePose pose;
  if (!PoseFromPlaneLines(lines, k, nominal, &pose)) return false;
  choice->rvec = cv::Mat(pose.rvec, true);
  choice->tvec = cv::Mat(pose.tvec, true);
  choice->line_rms_px = pose.rms_px;
  return true;
}

// How many of each slot's steps lie on the mask as the choice's pose projects it: a line that is
// not the mask's edge (an iso-angle line of the BRDF, a shadow) bends the pose away from the
// true edges, so the combination of true edges explains the most steps.
void Score(const std::vector<Slot>& slots, const cv::Matx33d& k, double inlier_px, Choice* choice) {
  choice->support = 0;
  choice->per_slot.assign(slots.size(), 0);
  for (std::size_t i = 0; i < slots.size(); ++i) {
    std::vector<cv::Point2d> ends;
    cv::projectPoints(std::vector<cv::Point3d>{{slots[i].a.x(), slots[i].a.y(), 0},
                                               {slots[i].b.x(), slots[i].b.y(), 0}},
                      choice->rvec, choice->tvec, cv::Mat(k), cv::noArray(), ends);
    const cv::Point2d d = ends[1] - ends[0];
    const double length = cv::norm(d);
    if (length < 1e-9) continue;
    const cv::Vec4d line(d.x / length, d.y / length, ends[0].x, ends[0].y);
    for (const cv::Point2d& p : slots[i].found.points) {
      choice->per_slot[i] += LineDistance(line, p) <= inlier_px;
    }
    choice->support += choice->per_slot[i];
  }
}

// Every combination of the slots' lines (and, where `may_omit`, of leaving a slot out), best
// first by support, then by the lines' consistency; false when none fixes a pose.
bool ChooseLines(const std::vector<Slot>& slots, const cv::Matx33d& k,
                 const geometry::CameraPose& nominal, double inlier_px, bool may_omit,
                 Choice* best) {
  const int first = may_omit ? kChooseNone : 0;
  std::vector<int> pick(slots.size(), first);
  bool found = false;
  for (;;) {
    bool usable = true;
    for (std::size_t i = 0; i < slots.size(); ++i) {
      usable &= pick[i] != kChooseNone || may_omit;
      usable &= pick[i] < static_cast<int>(slots[i].found.lines.size());
    }
    Choice choice;
    choice.pick = pick;
    if (usable && PoseFromLines(slots, k, nominal, &choice)) {
      Score(slots, k, inlier_px, &choice);
      if (!found || choice.support > best->support ||
          (choice.support == best->support && choice.line_rms_px < best->line_rms_px)) {
        *best = choice;
        found = true;
      }
    }
    // Next combination (mixed radix over the slots' line counts).
    std::size_t i = 0;
    for (; i < slots.size(); ++i) {
      if (++pick[i] < static_cast<int>(slots[i].found.lines.size())) break;
      pick[i] = first;
    }
    if (i == slots.size()) break;
  }
  return found;
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
  CheckOption(lines_per_edge >= 1, "TargetOptions.lines_per_edge", lines_per_edge, ">= 1");
  CheckOption(min_markers >= 2, "TargetOptions.min_markers", min_markers,
              ">= 2 (eight corners; fewer would not beat the cut-out's four)");
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
  // Clipped pixels keep their lower bound (saturation / shortest exposure), which joins the
  // unclipped values around them without a step and still marks the cut-out's edge.
  (void)valid;
  const EdgeImage image = MakeEdgeImage(radiance);
  EdgeLineOptions edge_options;
  edge_options.search_band_m =
      options.search_band * std::min(target.cutout_width, target.cutout_height);
  // On a marker mask the ring begins `gap` outside the cut-out: the band stays short of it, or
  // the markers' edges would compete with the cut-out's.
  if (target.markers) {
    edge_options.search_band_m = std::min(edge_options.search_band_m, 0.8 * target.markers->gap);
  }
  edge_options.corner_skip = options.corner_skip;
  edge_options.profile_step_px = options.profile_step_px;
  edge_options.min_log_step = options.min_log_step;
  edge_options.min_inlier_fraction = options.min_edge_fraction;
  edge_options.max_lines = options.lines_per_edge;
  const cv::Matx33d k = CameraMatrix(intrinsics);

  const auto search = [&](const std::array<geometry::Vec3, 4>& rectangle, int e) {
    const geometry::Vec3& a = rectangle[e];
    const geometry::Vec3& b = rectangle[(e + 1) % 4];
    return Slot{e % 2 == 0, e % 2 == 0 ? a.y() : a.x(), a, b,
                FindEdgeLines(image, intrinsics, nominal, a, b, edge_options)};
  };
  TargetCorners result;
  std::vector<Slot> cutout;
  std::string missing;
  for (int e = 0; e < 4; ++e) {
    cutout.push_back(search(WorldCorners(target), e));
    const EdgeLines& found = cutout.back().found;
    if (!found.lines.empty()) {
      ++result.cutout_edges_found;
    } else {
      missing += (missing.empty() ? "" : "; ") + std::string("edge ") + std::to_string(e) + ": " +
                 std::to_string(found.points.size()) + " steps on " +
                 std::to_string(found.profiles) + " profiles, none enough in a line";
    }
  }
  const double inlier_px = edge_options.inlier_px;
  const auto finish = [&](const std::vector<Slot>& slots, const Choice& choice) {
    double sum_sq = 0;
    int lines = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      const int pick = choice.pick[i];
      result.edge_points[i] = pick == kChooseNone ? 0 : slots[i].found.lines[pick].inliers;
      if (pick == kChooseNone) continue;
      sum_sq += std::pow(slots[i].found.lines[pick].rms_px, 2);
      ++lines;
    }
    result.line_rms_px = lines > 0 ? std::sqrt(sum_sq / lines) : 0;
  };
  // The four sides of the cut-out, one line each: the combination whose pose explains the most
  // steps, taken when its pose keeps every side (each on enough of its own steps).
  Choice choice;
  if (result.cutout_edges_found == 4 &&
      ChooseLines(cutout, k, nominal, inlier_px, false, &choice)) {
    bool consistent = true;
    for (std::size_t i = 0; i < 4; ++i) {
      consistent &= choice.per_slot[i] >= static_cast<std::size_t>(cutout[i].found.needed);
    }
    if (consistent) {
      // Corner k is where edge k-1 (arriving) meets edge k (leaving).
      for (int c = 0; c < 4; ++c) {
        if (!IntersectLines(cutout[(c + 3) % 4].found.lines[choice.pick[(c + 3) % 4]].line,
                            cutout[c].found.lines[choice.pick[c]].line, &result.corners[c])) {
          throw Error("target not found: two edges of the cut-out are parallel");
        }
      }
      finish(cutout, choice);
      return result;
    }
    result.cutout_edges_found = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      result.cutout_edges_found +=
          choice.per_slot[i] >= static_cast<std::size_t>(cutout[i].found.needed);
    }
    missing += std::string(missing.empty() ? "" : "; ") +
               "no combination of the sides' lines forms the cut-out";
  }
  // A side is blind (the sample as bright and as coloured as the paper there) or holds only
  // lines that are not the mask's: the paper's outline joins in, any side may be left out, and
  // the cut-out's corners are the projections of the best pose.
  if (options.use_paper_outline) {
    std::vector<Slot> slots = cutout;
    const auto paper = Rectangle(target.paper_width, target.paper_height);
    for (int e = 0; e < 4; ++e) {
      slots.push_back(search(paper, e));
      result.paper_edges_found += slots.back().found.lines.empty() ? 0 : 1;
    }
    // Eight slots, each left out or on one of its lines: two lines each keep the combinations
    // to 3^8 (the paper's outer edges, paper against the table, are rarely ambiguous).
    for (Slot& slot : slots) {
      if (slot.found.lines.size() > 2) slot.found.lines.resize(2);
    }
    if (ChooseLines(slots, k, nominal, inlier_px, true, &choice)) {
      std::vector<cv::Point3d> world;
      for (const geometry::Vec3& w : WorldCorners(target)) world.emplace_back(w.x(), w.y(), w.z());
      std::vector<cv::Point2d> projected;
      cv::projectPoints(world, choice.rvec, choice.tvec, cv::Mat(k), cv::noArray(), projected);
      std::copy(projected.begin(), projected.end(), result.corners.begin());
      result.cutout_edges_found = 0;
      for (std::size_t i = 0; i < 4; ++i)
        result.cutout_edges_found += choice.pick[i] != kChooseNone;
      finish(slots, choice);
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
  const std::vector<cv::Point2d> image(corners.corners.begin(), corners.corners.end());
  return PoseFromPlanePoints(object, image, intrinsics, nominal, options, "the cut-out's corners");
}

PoseEstimate PoseFromPlanePoints(const std::vector<cv::Point3d>& object,
                                 const std::vector<cv::Point2d>& image,
                                 const geometry::Intrinsics& intrinsics,
                                 const geometry::CameraPose& nominal, const TargetOptions& options,
                                 const std::string& what) {
  const cv::Mat k(CameraMatrix(intrinsics));
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(object, image, k, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE)) {
    throw Error("pose not found: " + what + " admit no planar pose");
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
  estimate.reprojection_rms_px = std::sqrt(sum_sq / static_cast<double>(image.size()));
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
    throw Error("implausible pose: " + what + " reproject with " +
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
