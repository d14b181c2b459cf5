#include "geometry/camera.h"

namespace brdfrig::geometry {

Eigen::Isometry3d WorldFromCameraLookingAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
  const Vec3 z = (target - eye).normalized();
  const Vec3 x = z.cross(up).normalized();
  const Vec3 y = z.cross(x);
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
  world_from_camera.linear().col(0) = x;
  world_from_camera.linear().col(1) = y;
  world_from_camera.linear().col(2) = z;
  world_from_camera.translation() = eye;
  return world_from_camera;
}

CameraPose LookAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
  CameraPose pose;
  pose.camera_from_world = WorldFromCameraLookingAt(eye, target, up).inverse();
  return pose;
}

bool ProjectToPixel(const Intrinsics& k, const CameraPose& pose, const Vec3& x_in_world,
                    Eigen::Vector2d* pixel) {
  const Vec3 x = pose.camera_from_world * x_in_world;
  if (x.z() <= 0) return false;
  const double xn = x.x() / x.z();
  const double yn = x.y() / x.z();
  const double r2 = xn * xn + yn * yn;
  const double d = 1 + k.k1 * r2 + k.k2 * r2 * r2;
  *pixel = {k.fx * xn * d + k.cx, k.fy * yn * d + k.cy};
  return true;
}

Vec3 PixelRayInWorld(const Intrinsics& k, const CameraPose& pose, const Eigen::Vector2d& pixel) {
  const double xd = (pixel.x() - k.cx) / k.fx;
  const double yd = (pixel.y() - k.cy) / k.fy;
  // Invert the radial model by fixed-point iteration (converges for realistic distortion).
  double xn = xd, yn = yd;
  if (k.k1 != 0 || k.k2 != 0) {
    for (int i = 0; i < 20; ++i) {
      const double r2 = xn * xn + yn * yn;
      const double d = 1 + k.k1 * r2 + k.k2 * r2 * r2;
      xn = xd / d;
      yn = yd / d;
    }
  }
  const Vec3 ray_in_camera = Vec3(xn, yn, 1).normalized();
  return pose.camera_from_world.linear().transpose() * ray_in_camera;
}

}  // namespace brdfrig::geometry
