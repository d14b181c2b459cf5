#include "calibrate/light_calibration.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "calibrate/linear_grey.h"
#include "common/error.h"
#include "common/format.h"
#include "common/option_check.h"

namespace brdfrig::calibrate {
namespace {

using geometry::Vec3;

// A photo's reflected ray: it leaves the sample plane at `origin` along `direction` (unit).
struct Ray {
  Vec3 origin, direction;
};

// The highlight's centre (pixels) in the cut-out: the intensity-weighted centroid of the part
// above half the peak that holds the peak (of the area clipped at full scale, if any).
cv::Point2d FindHighlight(const CalibrationPhoto& photo, const geometry::RigGeometry& rig,
                          const geometry::CameraPose& camera,
                          const LightCalibrationOptions& options) {
  const geometry::Intrinsics& k = rig.intrinsics;
  const geometry::TargetGeometry& t = rig.target;
  const double inset = options.edge_inset * std::min(t.cutout_width, t.cutout_height);
  const double hw = 0.5 * t.cutout_width - inset, hh = 0.5 * t.cutout_height - inset;
  // The cut-out's pixel box (projected corners, a margin for the distortion's bending).
  double x0 = k.width, y0 = k.height, x1 = 0, y1 = 0;
  for (const auto& [sx, sy] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    Eigen::Vector2d px;
    if (!geometry::ProjectToPixel(k, camera, Vec3(sx * hw, sy * hh, 0), &px)) continue;
    x0 = std::min(x0, px.x());
    y0 = std::min(y0, px.y());
    x1 = std::max(x1, px.x());
    y1 = std::max(y1, px.y());
  }
  const int margin = 8;
  const cv::Rect box =
      cv::Rect(cv::Point(static_cast<int>(x0) - margin, static_cast<int>(y0) - margin),
               cv::Point(static_cast<int>(x1) + margin + 1, static_cast<int>(y1) + margin + 1)) &
      cv::Rect(0, 0, k.width, k.height);
  if (box.width < 8 || box.height < 8) {
    throw Error(photo.name + ": the cut-out is not in view from the rig's pose");
  }
  const Vec3 centre = camera.CenterInWorld();
  cv::Mat inside(box.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) {
      const Vec3 ray = geometry::PixelRayInWorld(k, camera, {box.x + x, box.y + y});
      if (ray.z() >= 0) continue;
      const Vec3 p = centre - (centre.z() / ray.z()) * ray;
      if (std::abs(p.x()) <= hw && std::abs(p.y()) <= hh) inside.at<uchar>(y, x) = 255;
    }
  }
  cv::Mat grey = LinearGrey(photo.image)(box).clone();
  const cv::Mat clipped_mask = (grey >= 0.999f) & inside;
  if (options.smoothing_px > 0) cv::GaussianBlur(grey, grey, cv::Size(), options.smoothing_px);
  std::vector<float> values;
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) {
      if (inside.at<uchar>(y, x)) values.push_back(grey.at<float>(y, x));
    }
  }
  if (values.size() < 64) throw Error(photo.name + ": the cut-out is too small in the photo");
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2),
                   values.end());
  const double median = std::max<double>(values[values.size() / 2], 1e-6);
  double peak = 0;
  cv::Point peak_at;
  cv::minMaxLoc(grey, nullptr, &peak, nullptr, &peak_at, inside);
  if (!(peak > options.min_peak_ratio * median)) {
    throw Error(photo.name + ": no mirror highlight in the cut-out (the brightest spot is " +
                Fixed(peak / median, 1) + "x the median, at least " +
                Fixed(options.min_peak_ratio, 1) +
                "x needed): is the mirror tile in the cut-out, and the light's reflection in it?");
  }
  const bool clipped = cv::countNonZero(clipped_mask) > 0;
  const double threshold = 0.5 * (peak + median);
  cv::Mat blob = clipped ? clipped_mask : ((grey > threshold) & inside);
  cv::Mat labels;
  cv::connectedComponents(blob, labels, 8, CV_32S);
  int label = labels.at<int>(peak_at);
  if (label == 0) {  // the smoothed peak beside a clipped area: take the largest clipped part
    cv::Mat stats, centroids;
    const int n = cv::connectedComponentsWithStats(blob, labels, stats, centroids, 8, CV_32S);
    for (int i = 1; i < n; ++i) {
      if (label == 0 || stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(label, cv::CC_STAT_AREA))
        label = i;
    }
  }
  cv::Mat eroded;
  cv::erode(inside, eroded, cv::Mat(), cv::Point(-1, -1), 2);
  double sum_w = 0, sum_x = 0, sum_y = 0;
  for (int y = 0; y < box.height; ++y) {
    for (int x = 0; x < box.width; ++x) {
      if (label == 0 || labels.at<int>(y, x) != label) continue;
      if (!eroded.at<uchar>(y, x)) {
        throw Error(photo.name +
                    ": the highlight reaches the edge of the cut-out, so its centre is unknown: "
                    "choose positions whose mirror point lies well inside the cut-out");
      }
      const double w = clipped ? 1.0 : grey.at<float>(y, x) - threshold;
      sum_w += w;
      sum_x += w * x;
      sum_y += w * y;
    }
  }
  if (!(sum_w > 0)) throw Error(photo.name + ": no mirror highlight in the cut-out");
  return {box.x + sum_x / sum_w, box.y + sum_y / sum_w};
}

double Miss(const Ray& ray, const Vec3& light) {
  const Vec3 d = light - ray.origin;
  return (d - d.dot(ray.direction) * ray.direction).norm();
}

}  // namespace

void LightCalibrationOptions::Validate() const {
  CheckOption(min_photos >= 2, "LightCalibrationOptions.min_photos", min_photos, ">= 2");
  CheckOption(smoothing_px >= 0, "LightCalibrationOptions.smoothing_px", smoothing_px, ">= 0");
  CheckOption(min_peak_ratio > 1, "LightCalibrationOptions.min_peak_ratio", min_peak_ratio, "> 1");
  CheckOption(edge_inset >= 0 && edge_inset < 0.4, "LightCalibrationOptions.edge_inset", edge_inset,
              "in [0, 0.4)");
  CheckOption(max_dilution > 1, "LightCalibrationOptions.max_dilution", max_dilution, "> 1");
  CheckOption(max_miss_m > 0, "LightCalibrationOptions.max_miss_m", max_miss_m, "> 0");
}

std::string LightCalibrationResult::ToString() const {
  std::ostringstream out;
  out << "light at rest (" << Fixed(1e3 * light_position.x(), 2) << ", "
      << Fixed(1e3 * light_position.y(), 2) << ", " << Fixed(1e3 * light_position.z(), 2)
      << ") mm, " << Fixed(1e3 * nominal_offset_m, 2) << " mm from the nominal; from "
      << photos.size() << " photos, RMS miss " << Fixed(1e3 * rms_miss_m, 3) << " mm, dilution "
      << Fixed(dilution, 1) << "\n";
  for (const LightPhotoResult& p : photos) {
    out << "  " << p.name << ": highlight (" << Fixed(p.highlight_x, 2) << ", "
        << Fixed(p.highlight_y, 2) << ") px, ray misses by " << Fixed(1e3 * p.miss_m, 3) << " mm\n";
  }
  return out.str();
}

LightCalibrationResult CalibrateLight(const std::vector<LightPhoto>& photos,
                                      const geometry::RigGeometry& rig,
                                      const LightCalibrationOptions& options) {
  options.Validate();
  if (static_cast<int>(photos.size()) < options.min_photos) {
    throw Error("light calibration: " + std::to_string(photos.size()) + " photos; at least " +
                std::to_string(options.min_photos) +
                " are needed, at positions that put the mirror point in different parts of the "
                "cut-out");
  }
  const geometry::Intrinsics& k = rig.intrinsics;
  LightCalibrationResult result;
  // Each photo's constraint on the rest position x: the moved light A x + b lies on the ray, so
  // P (A x + b - o) = 0 with P the projection across the ray. Normal equations, summed.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Vec3 rhs = Vec3::Zero();
  std::vector<Ray> rays;
  std::vector<Eigen::Isometry3d> motions;
  for (const LightPhoto& lp : photos) {
    if (lp.photo.image.cols != k.width || lp.photo.image.rows != k.height) {
      throw Error(lp.photo.name + ": " + std::to_string(lp.photo.image.cols) + "x" +
                  std::to_string(lp.photo.image.rows) + ", not the rig camera's " +
                  std::to_string(k.width) + "x" + std::to_string(k.height) +
                  " (a photo of another camera?)");
    }
    const geometry::CameraPose camera = rig.CameraAt(lp.positions);
    const cv::Point2d at = FindHighlight(lp.photo, rig, camera, options);
    const Vec3 centre = camera.CenterInWorld();
    const Vec3 view = geometry::PixelRayInWorld(k, camera, {at.x, at.y});
    const Vec3 origin = centre - (centre.z() / view.z()) * view;
    const Ray ray{origin, Vec3(view.x(), view.y(), -view.z()).normalized()};
    const Eigen::Isometry3d motion = rig.LightMotion(lp.positions);
    const Eigen::Matrix3d across =
        Eigen::Matrix3d::Identity() - ray.direction * ray.direction.transpose();
    const Eigen::Matrix3d a = motion.linear();
    normal += a.transpose() * across * a;
    rhs += a.transpose() * across * (ray.origin - motion.translation());
    rays.push_back(ray);
    motions.push_back(motion);
    result.photos.push_back({lp.photo.name, at.x, at.y, 0});
  }
  // Each ray pins the light across itself (eigenvalue 1 per ray); the weakest direction's
  // eigenvalue says how well the rays together pin it there.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(normal);
  const double weakest = eigen.eigenvalues().minCoeff();
  result.dilution = weakest > 0 ? 1 / std::sqrt(weakest) : INFINITY;
  if (!(result.dilution <= options.max_dilution)) {
    throw Error(
        "light calibration: the photos' reflected rays nearly coincide, so they cannot "
        "tell where along them the light is (dilution " +
        Fixed(result.dilution, 1) + ", at most " + Fixed(options.max_dilution, 1) +
        "): add positions whose mirror points lie far apart in the cut-out");
  }
  result.light_position = normal.ldlt().solve(rhs);
  result.nominal_offset_m = (result.light_position - rig.light_position).norm();
  double squares = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    LightPhotoResult& p = result.photos[i];
    p.miss_m = Miss(rays[i], motions[i] * result.light_position);
    squares += p.miss_m * p.miss_m;
  }
  result.rms_miss_m = std::sqrt(squares / static_cast<double>(rays.size()));
  for (const LightPhotoResult& p : result.photos) {
    if (p.miss_m > options.max_miss_m) {
      throw Error(p.name + ": its reflected ray misses the light the other photos agree on by " +
                  Fixed(1e3 * p.miss_m, 2) + " mm (at most " + Fixed(1e3 * options.max_miss_m, 2) +
                  " mm): is the tile flat on the sample plane, and each photo at the position "
                  "given for it?");
    }
  }
  if (!(result.light_position.z() > 0)) {
    throw Error("light calibration: the rays meet below the sample plane: not a mirror tile");
  }
  return result;
}

}  // namespace brdfrig::calibrate
