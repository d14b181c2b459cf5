#include "reconstruct/predict_photo.h"

#include <algorithm>

#include "common/parallel.h"

namespace brdfrig::reconstruct {

PredictedSample PredictSampleRadiance(const brdf::Brdf& material, const cv::Mat& valid,
                                      const PlaneView& view, const geometry::Vec3& light,
                                      const Radiometry& radiometry,
                                      const geometry::TargetGeometry& target,
                                      const SampleOptions& options) {
  options.Validate();
  const geometry::Vec3 n = geometry::Vec3::UnitZ();
  const SampleRegion region = SampleRegionOf(view, target, options);
  const PlaneView::Box& box = region.box;
  const geometry::Vec3& camera = view.camera_centre();
  PredictedSample out;
  out.radiance = cv::Mat(valid.size(), CV_32FC3, cv::Scalar::all(0));
  out.mask = cv::Mat(valid.size(), CV_8UC1, cv::Scalar(0));
  ParallelFor(static_cast<std::size_t>(std::max(box.y1 - box.y0, 0)), [&](std::size_t begin,
                                                                          std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      const int y = box.y0 + static_cast<int>(r);
      for (int x = box.x0; x < box.x1; ++x) {
        const auto p = view.PointAt(x, y);
        if (!p || !region.Contains(*p) || !valid.at<uchar>(y, x)) {
          continue;
        }
        const double e = PointLightIrradiance(light, *p);
        if (!(e > 0)) continue;
        const brdf::Rgb f = material.Eval((light - *p).normalized(), (camera - *p).normalized(), n);
        const cv::Vec3d k = radiometry.ScaleAt(x, y);
        // R,G,B material channels → B,G,R image.
        out.radiance.at<cv::Vec3f>(y, x) =
            cv::Vec3f(static_cast<float>(f[2] * k[0] * e), static_cast<float>(f[1] * k[1] * e),
                      static_cast<float>(f[0] * k[2] * e));
        out.mask.at<uchar>(y, x) = 255;
      }
    }
  });
  return out;
}

}  // namespace brdfrig::reconstruct
