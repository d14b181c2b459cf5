#include "reconstruct/plane_view.h"

#include <algorithm>
#include <cmath>

namespace brdfrig::reconstruct {

PlaneView::PlaneView(const geometry::Intrinsics& intrinsics, const geometry::CameraPose& pose)
    : intrinsics_(intrinsics), pose_(pose), centre_(pose.CenterInWorld()) {}

std::optional<geometry::Vec3> PlaneView::PointAt(double x, double y) const {
  const geometry::Vec3 ray = geometry::PixelRayInWorld(intrinsics_, pose_, {x, y});
  if (ray.z() * centre_.z() >= 0) return std::nullopt;
  return centre_ + ray * (-centre_.z() / ray.z());
}

PlaneView::Box PlaneView::PixelBox(double half_w, double half_h) const {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  // The rectangle's outline, densely, so radial distortion cannot bow an edge outside the box.
  for (int i = 0; i <= 64; ++i) {
    const double t = -1 + 2.0 * i / 64;
    for (const geometry::Vec3& p :
         {geometry::Vec3(t * half_w, -half_h, 0), geometry::Vec3(t * half_w, half_h, 0),
          geometry::Vec3(-half_w, t * half_h, 0), geometry::Vec3(half_w, t * half_h, 0)}) {
      Eigen::Vector2d pixel;
      if (!geometry::ProjectToPixel(intrinsics_, pose_, p, &pixel)) continue;
      x0 = std::min(x0, pixel.x());
      y0 = std::min(y0, pixel.y());
      x1 = std::max(x1, pixel.x());
      y1 = std::max(y1, pixel.y());
    }
  }
  Box box;
  if (x0 > x1) return box;
  box.x0 = std::clamp(static_cast<int>(std::floor(x0)), 0, intrinsics_.width);
  box.y0 = std::clamp(static_cast<int>(std::floor(y0)), 0, intrinsics_.height);
  box.x1 = std::clamp(static_cast<int>(std::ceil(x1)) + 1, 0, intrinsics_.width);
  box.y1 = std::clamp(static_cast<int>(std::ceil(y1)) + 1, 0, intrinsics_.height);
  return box;
}

double PointLightIrradiance(const geometry::Vec3& light, const geometry::Vec3& x) {
  const geometry::Vec3 d = light - x;
  const double d2 = d.squaredNorm();
  return std::max(d.z(), 0.0) / (d2 * std::sqrt(d2));
}

}  // namespace brdfrig::reconstruct
