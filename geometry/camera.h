// Cameras: pinhole intrinsics with radial distortion, rigid poses, the look-at construction,
// projection of world points and rays through pixels. Conventions (OpenCV): camera x right,
// y down, z forward; transforms are named target_from_source, points x_in_frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace brdfrig::geometry {

using Vec3 = Eigen::Vector3d;

// Pinhole camera with radial distortion (OpenCV convention: x right, y down, z forward).
struct Intrinsics {
  int width = 0, height = 0;  // pixels
  double fx = 0, fy = 0;      // focal length in pixels
  double cx = 0, cy = 0;      // principal point in pixels
  double k1 = 0, k2 = 0;      // radial distortion (OpenCV model); 0 = none
};

// A rigid transform x_in_camera = camera_from_world * x_in_world.
struct CameraPose {
  Eigen::Isometry3d camera_from_world = Eigen::Isometry3d::Identity();
  Vec3 CenterInWorld() const { return camera_from_world.inverse().translation(); }
};

// The camera at `eye` looking at `target`, with the world direction `up` appearing up in the
// image (the image's y axis points away from it). `up` must not be along the view direction.
// WorldFromCameraLookingAt is the same transform, the other way round.
CameraPose LookAt(const Vec3& eye, const Vec3& target, const Vec3& up);
Eigen::Isometry3d WorldFromCameraLookingAt(const Vec3& eye, const Vec3& target, const Vec3& up);

// Projects a world point to pixel coordinates (with distortion). Returns false when the point is
// behind the camera.
bool ProjectToPixel(const Intrinsics& k, const CameraPose& pose, const Vec3& x_in_world,
                    Eigen::Vector2d* pixel);

// Unit ray direction in world space through a pixel (undistorted first), and the camera centre.
Vec3 PixelRayInWorld(const Intrinsics& k, const CameraPose& pose, const Eigen::Vector2d& pixel);

}  // namespace brdfrig::geometry
