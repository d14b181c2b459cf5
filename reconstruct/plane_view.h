// Where each pixel looks on the sample plane (z = 0) for a measured camera pose, and the angles
// the slice model needs there. Shared by the highlight search, the paper calibration and the
// sample extraction so that all three agree on the geometry of a pixel.
#pragma once

#include <optional>

#include "geometry/camera.h"

namespace brdfrig::reconstruct {

class PlaneView {
 public:
  PlaneView(const geometry::Intrinsics& intrinsics, const geometry::CameraPose& pose);

  // The plane point seen through the pixel's centre ((x, y) are pixel indices); nullopt when
  // the ray misses the plane (looks away from it).
  std::optional<geometry::Vec3> PointAt(double x, double y) const;
  const geometry::Vec3& camera_centre() const { return centre_; }

  // Axis-aligned pixel box covering the plane rectangle |x| <= half_w, |y| <= half_h, clipped to
  // the image: [x0, x1) × [y0, y1).
  struct Box {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  Box PixelBox(double half_w, double half_h) const;

 private:
  geometry::Intrinsics intrinsics_;
  geometry::CameraPose pose_;
  geometry::Vec3 centre_;
};

// Irradiance factor cos(theta_l) / d² at a plane point for a point light (unit intensity).
double PointLightIrradiance(const geometry::Vec3& light, const geometry::Vec3& x);

}  // namespace brdfrig::reconstruct
