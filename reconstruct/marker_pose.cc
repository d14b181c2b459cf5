#include "reconstruct/marker_pose.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include "calibrate/charuco_spec.h"
#include "calibrate/marker_mask.h"

namespace brdfrig::reconstruct {
namespace {

// The merged radiance as the 8-bit grey ArUco's detector reads: invalid pixels white, the 90th
// percentile of the valid ones (the paper, which covers most of the frame) at 200, so a clipped
// highlight saturates while the printed black stays black.
cv::Mat DetectionImage(const cv::Mat& radiance, const cv::Mat& valid) {
  cv::Mat grey;
  cv::transform(radiance, grey, cv::Matx13f(1.f / 3, 1.f / 3, 1.f / 3));
  std::vector<float> values;
  values.reserve(grey.total());
  for (int y = 0; y < grey.rows; ++y) {
    const float* g = grey.ptr<float>(y);
    const std::uint8_t* v = valid.ptr<std::uint8_t>(y);
    for (int x = 0; x < grey.cols; ++x) {
      if (v[x] != 0 && std::isfinite(g[x])) values.push_back(g[x]);
    }
  }
  cv::Mat out(grey.size(), CV_8U, cv::Scalar(255));
  if (values.empty()) return out;
  const auto p90 = values.begin() + static_cast<long>(values.size() * 9 / 10);
  std::nth_element(values.begin(), p90, values.end());
  const double white = std::max(1e-12, static_cast<double>(*p90));
  grey.convertTo(out, CV_8U, 200.0 / white);
  out.setTo(255, valid == 0);
  return out;
}

}  // namespace

MarkerCorners FindMaskMarkers(const cv::Mat& radiance, const cv::Mat& valid,
                              const geometry::Intrinsics& intrinsics,
                              const geometry::TargetGeometry& target) {
  MarkerCorners found;
  if (!target.markers) return found;
  const calibrate::MarkerMaskSpec spec = calibrate::MarkerMaskSpec::ForTarget(target);
  spec.Validate();
  std::map<int, const calibrate::MaskMarker*> printed;
  const std::vector<calibrate::MaskMarker> markers = calibrate::MaskMarkers(spec);
  for (const calibrate::MaskMarker& m : markers) printed[m.id] = &m;

  const cv::Mat image = DetectionImage(radiance, valid);
  const cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  // Corners refined on the image's gradients (cornerSubPix): measured on simulated captures,
  // 0.2-0.3 px RMS against 0.6-0.7 px for corners from lines fitted to the contour.
  parameters->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(image, calibrate::DictionaryNamed(spec.dictionary), corners, ids,
                           parameters);
  std::map<int, int> seen;
  for (int id : ids) ++seen[id];
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto it = printed.find(ids[i]);
    // Another target's marker, or a false detection; an id found twice is trusted in neither.
    if (it == printed.end() || seen[ids[i]] > 1) continue;
    ++found.markers;
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector2d& w = it->second->corners[c];
      found.world.emplace_back(w.x(), w.y(), 0.0);
      found.image.push_back(UndistortPixel(intrinsics, cv::Point2d(corners[i][c])));
    }
  }
  return found;
}

}  // namespace brdfrig::reconstruct
