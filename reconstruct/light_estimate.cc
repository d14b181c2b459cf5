#include "reconstruct/light_estimate.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "common/angles.h"
#include "common/error.h"
#include "common/format.h"

namespace brdfrig::reconstruct {
namespace {

double AngleBetween(const geometry::Vec3& a, const geometry::Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

void LightOptions::Validate() const {
  if (!(smoothing_px >= 0)) throw OptionsError("LightOptions.smoothing_px must be >= 0");
  if (!(min_peak_ratio > 1)) throw OptionsError("LightOptions.min_peak_ratio must be > 1");
  if (!(edge_inset >= 0 && edge_inset < 0.4)) {
    throw OptionsError("LightOptions.edge_inset must be in [0, 0.4)");
  }
  if (!(max_nominal_disagreement_deg > 0 && max_nominal_disagreement_deg <= 90)) {
    throw OptionsError("LightOptions.max_nominal_disagreement_deg = " +
                       std::to_string(max_nominal_disagreement_deg) + "; must be in (0, 90]");
  }
}

const char* LightEstimate::Source() const {
  return from_calibration ? "calibration" : from_highlight ? "highlight" : "nominal";
}

LightEstimate EstimateLight(const cv::Mat& radiance, const cv::Mat& valid, const PlaneView& view,
                            const geometry::TargetGeometry& target,
                            const geometry::Vec3& nominal_light, const LightOptions& options) {
  options.Validate();
  LightEstimate estimate;
  estimate.position = nominal_light;
  if (!options.use_highlight) {
    estimate.from_calibration = true;
    return estimate;
  }
  const double half_w = target.cutout_width / 2, half_h = target.cutout_height / 2;
  const double inset = options.edge_inset * std::min(target.cutout_width, target.cutout_height);
  const PlaneView::Box box = view.PixelBox(half_w, half_h);
  if (box.x1 - box.x0 < 3 || box.y1 - box.y0 < 3) {
    estimate.warnings.push_back("cut-out not in the image: nominal light used");
    return estimate;
  }
  const cv::Rect roi(box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0);
  // Which ROI pixels are inside the cut-out (inset from its border).
  cv::Mat inside(roi.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < roi.height; ++y) {
    for (int x = 0; x < roi.width; ++x) {
      const auto p = view.PointAt(x + roi.x, y + roi.y);
      if (p && std::abs(p->x()) < half_w - inset && std::abs(p->y()) < half_h - inset) {
        inside.at<uchar>(y, x) = 255;
      }
    }
  }
  if (cv::countNonZero(inside) < 16) {
    estimate.warnings.push_back("cut-out too small in the image: nominal light used");
    return estimate;
  }
  cv::Mat lum;
  cv::cvtColor(radiance(roi), lum, cv::COLOR_BGR2GRAY);
  if (options.smoothing_px > 0) cv::GaussianBlur(lum, lum, cv::Size(), options.smoothing_px);

  // The blob to locate: pixels clipped in every exposure if there are any (their values are only
  // lower bounds), else those above half the way from the median to the peak.
  cv::Mat clipped;
  cv::bitwise_and(inside, ~valid(roi), clipped);
  cv::Mat blob;
  double peak = 0, median = 0;
  cv::Point peak_at;
  {
    std::vector<float> values;
    values.reserve(static_cast<std::size_t>(cv::countNonZero(inside)));
    for (int y = 0; y < roi.height; ++y) {
      for (int x = 0; x < roi.width; ++x) {
        if (inside.at<uchar>(y, x)) values.push_back(lum.at<float>(y, x));
      }
    }
    std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2),
                     values.end());
    median = values[values.size() / 2];
    cv::minMaxLoc(lum, nullptr, &peak, nullptr, &peak_at, inside);
  }
  if (cv::countNonZero(clipped) > 0) {
    estimate.saturated_peak = true;
    estimate.warnings.push_back(
        "highlight clipped in every exposure: its centre is taken from the clipped area, and "
        "the peak value A1 rests on the lobe's shape (add a shorter exposure)");
    blob = clipped;
    cv::minMaxLoc(lum, nullptr, &peak, nullptr, &peak_at, clipped);
  } else {
    if (!(peak > options.min_peak_ratio * median)) {
      estimate.warnings.push_back("no highlight in the cut-out (peak only " +
                                  std::to_string(peak / std::max(median, 1e-30)) +
                                  "× the median): nominal light used");
      return estimate;
    }
    cv::threshold(lum, blob, 0.5 * (peak + median), 255, cv::THRESH_BINARY);
    blob.convertTo(blob, CV_8U);
    cv::bitwise_and(blob, inside, blob);
  }
  // Keep the connected part of the blob that holds the peak.
  cv::Mat labels;
  cv::connectedComponents(blob, labels, 8, CV_32S);
  const int label = labels.at<int>(peak_at);
  double sum_w = 0, sum_x = 0, sum_y = 0;
  bool touches_border = false;
  const double threshold = estimate.saturated_peak ? 0 : 0.5 * (peak + median);
  for (int y = 0; y < roi.height; ++y) {
    for (int x = 0; x < roi.width; ++x) {
      if (labels.at<int>(y, x) != label || label == 0) continue;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= roi.width || ny >= roi.height || !inside.at<uchar>(ny, nx)) {
          touches_border = true;
        }
      }
      const double w = estimate.saturated_peak ? 1.0 : lum.at<float>(y, x) - threshold;
      sum_w += w;
      sum_x += w * x;
      sum_y += w * y;
    }
  }
  // A broad lobe's half-maximum area may reach the cut-out's border while its peak is well
  // inside: then the smoothed peak is the start (the centroid would be cut off). Only a peak on
  // the border itself means the mirror point is at the edge or outside.
  const int border_px = 3;
  const cv::Rect interior(border_px, border_px, roi.width - 2 * border_px,
                          roi.height - 2 * border_px);
  cv::Mat eroded;
  cv::erode(inside, eroded, cv::Mat(), cv::Point(-1, -1), border_px);
  if (!(sum_w > 0) || !interior.contains(peak_at) || !eroded.at<uchar>(peak_at)) {
    estimate.warnings.push_back(
        "highlight at the edge of the cut-out or outside it: nominal light used");
    return estimate;
  }
  estimate.highlight_px = touches_border
                              ? cv::Point2d(roi.x + peak_at.x, roi.y + peak_at.y)
                              : cv::Point2d(roi.x + sum_x / sum_w, roi.y + sum_y / sum_w);
  const auto x = view.PointAt(estimate.highlight_px.x, estimate.highlight_px.y);
  if (!x) return estimate;
  const geometry::Vec3 v = (view.camera_centre() - *x).normalized();
  const geometry::Vec3 l(-v.x(), -v.y(), v.z());  // mirror of v about the normal +z
  const double disagreement = AngleBetween(l, nominal_light - *x);
  if (disagreement > Radians(options.max_nominal_disagreement_deg)) {
    estimate.warnings.push_back(
        "the brightest spot (" + Fixed(estimate.highlight_px.x, 0) + ", " +
        Fixed(estimate.highlight_px.y, 0) + " px) would put the light " +
        Fixed(Degrees(disagreement), 1) + "° from the rig's nominal light (more than " +
        Fixed(options.max_nominal_disagreement_deg, 1) +
        "°): not the mirror highlight; nominal light used (if the rig file is off, fix it)");
    estimate.highlight_px = {-1, -1};
    return estimate;
  }
  const double distance = (nominal_light - *x).norm();
  estimate.position = *x + l * distance;
  estimate.highlight_in_world = *x;
  estimate.from_highlight = true;
  estimate.nominal_disagreement_rad = disagreement;
  return estimate;
}

}  // namespace brdfrig::reconstruct
