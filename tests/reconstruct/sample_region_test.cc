// The slice samples and the direction samples read the very same pixels of a photo: those whose
// plane point lies in SampleRegionOf (the cut-out less its edge margin).
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "geometry/camera.h"
#include "reconstruct/direction_samples.h"
#include "reconstruct/samples.h"

namespace brdfrig::reconstruct {
namespace {

struct Photo {
  PlaneView view;
  cv::Mat radiance, valid;
  Radiometry radiometry;
  geometry::TargetGeometry target;  // 100 mm square cut-out
  geometry::Vec3 light{0.2, 0.1, 0.5};
};

// A uniformly bright 640x480 photo taken 0.4 m away, 30° from the normal.
Photo MakePhoto() {
  geometry::Intrinsics k;
  k.width = 640;
  k.height = 480;
  k.fx = k.fy = 900;
  k.cx = 320;
  k.cy = 240;
  const double tilt = 30 * M_PI / 180;
  const geometry::Vec3 eye(0.4 * std::sin(tilt), 0, 0.4 * std::cos(tilt));
  Photo photo{PlaneView(k, geometry::LookAt(eye, geometry::Vec3::Zero(), geometry::Vec3::UnitY())),
              cv::Mat(k.height, k.width, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5)),
              cv::Mat(k.height, k.width, CV_8U, cv::Scalar(1))};
  photo.radiometry.scale = cv::Vec3d(1, 1, 1);
  photo.radiometry.width = k.width;
  photo.radiometry.height = k.height;
  return photo;
}

// Pixels whose plane point the region contains, counted here independently of the extractors.
int PixelsInRegion(const Photo& photo, const SampleOptions& options) {
  const SampleRegion region = SampleRegionOf(photo.view, photo.target, options);
  int count = 0;
  for (int y = 0; y < photo.radiance.rows; ++y) {
    for (int x = 0; x < photo.radiance.cols; ++x) {
      const auto p = photo.view.PointAt(x, y);
      if (p && region.Contains(*p)) ++count;
    }
  }
  return count;
}

TEST(SampleRegion, SliceAndDirectionSamplesReadExactlyTheRegionsPixels) {
  const Photo photo = MakePhoto();
  int previous = 0;
  for (const double margin : {0.2, 0.04, 0.0}) {
    SampleOptions options;
    options.edge_margin = margin;
    const int expected = PixelsInRegion(photo, options);
    ASSERT_GT(expected, 1000) << "margin " << margin;
    const BrdfSamples slice = ExtractSamples(photo.radiance, photo.valid, photo.view, photo.light,
                                             photo.radiometry, photo.target, options);
    const DirectionSamples directions =
        ExtractDirectionSamples(photo.radiance, photo.valid, /*noise_floor=*/0, photo.view,
                                photo.light, photo.radiometry, photo.target, options, {});
    EXPECT_EQ(slice.pixels_used, expected) << "margin " << margin;
    EXPECT_EQ(directions.pixels_used, expected) << "margin " << margin;
    // A narrower margin reads more of the cut-out.
    EXPECT_GT(expected, previous) << "margin " << margin;
    previous = expected;
  }
}

}  // namespace
}  // namespace brdfrig::reconstruct
