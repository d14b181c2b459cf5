#include "reconstruct/target.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::reconstruct {
namespace {

constexpr int kProfileSamples = 256;

// Luminance, floored relative to the image's mean so that black pixels do not dominate its log.
cv::Mat Luminance(const cv::Mat& radiance) {
  cv::Mat gray;
  cv::cvtColor(radiance, gray, cv::COLOR_BGR2GRAY);
  const double floor = std::max(cv::mean(gray)[0] * 1e-3, 1e-12);
  cv::max(gray, floor, gray);
  return gray;
}

float Bilinear(const cv::Mat& image, const cv::Point2d& p) {
  const double x = std::clamp(p.x, 0.0, image.cols - 1.001);
  const double y = std::clamp(p.y, 0.0, image.rows - 1.001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double fx = x - x0, fy = y - y0;
  const float* r0 = image.ptr<float>(y0);
  const float* r1 = image.ptr<float>(y0 + 1);
  return static_cast<float>((1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) +
                            fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]));
}

bool Project(const geometry::Intrinsics& k, const geometry::CameraPose& pose,
             const geometry::Vec3& x, cv::Point2d* pixel) {
  Eigen::Vector2d p;
  if (!geometry::ProjectToPixel(k, pose, x, &p)) return false;
  *pixel = {p.x(), p.y()};
  return true;
}

std::array<geometry::Vec3, 4> WorldCorners(const geometry::TargetGeometry& target) {
  const double w = target.cutout_width / 2, h = target.cutout_height / 2;
  return {geometry::Vec3(-w, -h, 0), geometry::Vec3(w, -h, 0), geometry::Vec3(w, h, 0),
          geometry::Vec3(-w, h, 0)};
}

// Fits a line to points (Huber), drops points farther than 3 px and refits once.
cv::Vec4d FitEdgeLine(std::vector<cv::Point2d> points, double* rms) {
  cv::Vec4d line;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<cv::Point2f> as_float(points.begin(), points.end());
    cv::Vec4f fitted;
    cv::fitLine(as_float, fitted, cv::DIST_HUBER, 0, 0.01, 0.01);
    line = cv::Vec4d(fitted[0], fitted[1], fitted[2], fitted[3]);
    // Refine the float fit in double: least squares through the centroid along the normal.
    std::vector<cv::Point2d> kept;
    double sum_sq = 0;
    for (const auto& p : points) {
      const double d = std::abs((p.x - line[2]) * line[1] - (p.y - line[3]) * line[0]);
      if (d <= 3.0) {
        kept.push_back(p);
        sum_sq += d * d;
      }
    }
    *rms = kept.empty() ? 0 : std::sqrt(sum_sq / static_cast<double>(kept.size()));
    if (kept.size() < 2) break;
    points = std::move(kept);
  }
  // Total least squares on the kept points (double precision).
  cv::Point2d mean(0, 0);
  for (const auto& p : points) mean += p;
  mean *= 1.0 / static_cast<double>(points.size());
  double sxx = 0, sxy = 0, syy = 0;
  for (const auto& p : points) {
    const cv::Point2d d = p - mean;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
  return {std::cos(angle), std::sin(angle), mean.x, mean.y};
}

cv::Point2d Intersect(const cv::Vec4d& a, const cv::Vec4d& b) {
  // a: p = (a2,a3) + s (a0,a1); solve for the crossing with b.
  const double det = a[0] * (-b[1]) - a[1] * (-b[0]);
  if (std::abs(det) < 1e-12) throw Error("target not found: two edges of the cut-out are parallel");
  const double dx = b[2] - a[2], dy = b[3] - a[3];
  const double s = (dx * (-b[1]) - dy * (-b[0])) / det;
  return {a[2] + s * a[0], a[3] + s * a[1]};
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
  const cv::Mat lum = Luminance(radiance);
  const auto world = WorldCorners(target);
  const double band = options.search_band * std::min(target.cutout_width, target.cutout_height);
  std::array<cv::Vec4d, 4> lines;
  TargetCorners result;
  double rms_sum = 0;
  for (int e = 0; e < 4; ++e) {
    const geometry::Vec3 a = world[e], b = world[(e + 1) % 4];
    const geometry::Vec3 along = (b - a).normalized();
    const geometry::Vec3 outward = along.cross(geometry::Vec3::UnitZ()).normalized() *
                                   (along.cross(geometry::Vec3::UnitZ()).dot(a) > 0 ? 1.0 : -1.0);
    cv::Point2d pa, pb;
    if (!Project(intrinsics, nominal, a, &pa) || !Project(intrinsics, nominal, b, &pb)) {
      throw Error("target not found: the nominal pose puts the cut-out behind the camera");
    }
    const int profiles =
        std::max(8, static_cast<int>(cv::norm(pb - pa) * (1 - 2 * options.corner_skip) /
                                     options.profile_step_px));
    std::vector<cv::Point2d> points;
    std::array<cv::Point2d, kProfileSamples> pixel;
    std::array<float, kProfileSamples> linear, value;  // luminance and its log
    for (int i = 0; i < profiles; ++i) {
      const double t = options.corner_skip + (1 - 2 * options.corner_skip) * (i + 0.5) / profiles;
      const geometry::Vec3 on_edge = a + t * (b - a);
      bool inside = true;
      for (int j = 0; j < kProfileSamples; ++j) {
        const double u = band * (2.0 * j / (kProfileSamples - 1) - 1);
        if (!Project(intrinsics, nominal, on_edge + u * outward, &pixel[j]) || pixel[j].x < 1 ||
            pixel[j].y < 1 || pixel[j].x > radiance.cols - 2 || pixel[j].y > radiance.rows - 2) {
          inside = false;
          break;
        }
        linear[j] = Bilinear(lum, pixel[j]);
        value[j] = std::log(linear[j]);
      }
      if (!inside) continue;
      int best = -1;
      double best_gradient = 0;
      for (int j = 2; j + 2 < kProfileSamples; ++j) {
        const double g = std::abs(value[j + 1] - value[j - 1]);
        if (g > best_gradient) {
          best_gradient = g;
          best = j;
        }
      }
      // Levels on either side, 2 px from the steepest point: past an area-sampled edge's ramp.
      const double spacing = std::max(cv::norm(pixel[1] - pixel[0]), 1e-6);
      const int reach = std::max(2, static_cast<int>(std::ceil(2.0 / spacing)));
      if (best - 2 * reach < 0 || best + 2 * reach >= kProfileSamples) continue;  // band border
      const double step = std::abs(value[best + reach] - value[best - reach]);
      if (step < options.min_log_step) continue;
      // Sub-pixel position by area: an area-sampled edge (and its linear interpolation along
      // the profile) holds exactly as much of the left side's light as the left side's extent,
      // so the edge lies at the start plus the integral of the left side's fraction. Each side
      // is extrapolated linearly (the sample's side is rarely flat: the lobe falls off across
      // it). Interpolating to a half level instead would be biased by up to 0.08 px.
      const auto side = [&](int near, int far, int j) {
        const double slope = (linear[near] - linear[far]) / (near - far);
        return linear[near] + slope * (j - near);
      };
      const auto left_fraction = [&](int j) {
        const double left = side(best - reach, best - 2 * reach, j);
        const double right = side(best + reach, best + 2 * reach, j);
        return std::clamp((linear[j] - right) / (left - right), 0.0, 1.0);
      };
      double crossing = best - reach;
      for (int j = best - reach; j < best + reach; ++j) {
        crossing += 0.5 * (left_fraction(j) + left_fraction(j + 1));
      }
      const int j0 = std::clamp(static_cast<int>(std::floor(crossing)), 0, kProfileSamples - 2);
      const cv::Point2d p = pixel[j0] + (crossing - j0) * (pixel[j0 + 1] - pixel[j0]);
      points.push_back(UndistortPixel(intrinsics, p));
    }
    result.edge_points[e] = static_cast<int>(points.size());
    if (points.size() <
        std::max<std::size_t>(4, static_cast<std::size_t>(options.min_edge_fraction * profiles))) {
      throw Error("target not found: edge " + std::to_string(e) + " of the cut-out shows a clear " +
                  "step at only " + std::to_string(points.size()) + " of " +
                  std::to_string(profiles) +
                  " places near where the rig's nominal pose puts it (is the mask in view, "
                  "the rig geometry right, the exposure sensible?)");
    }
    double rms = 0;
    lines[e] = FitEdgeLine(points, &rms);
    rms_sum += rms * rms;
  }
  // Corner k is where edge k-1 (arriving) meets edge k (leaving).
  for (int k = 0; k < 4; ++k) result.corners[k] = Intersect(lines[(k + 3) % 4], lines[k]);
  result.line_rms_px = std::sqrt(rms_sum / 4);
  return result;
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
