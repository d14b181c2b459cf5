// The one interface every material model implements: an isotropic BRDF evaluated for unit
// directions in world space. Values are in 1/sr, per colour channel (linear RGB).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace brdfrig::brdf {

using Vec3 = Eigen::Vector3d;
using Rgb = Eigen::Array3d;

// Rgb's channels as files and messages name them.
inline constexpr const char* kChannelNames[3] = {"red", "green", "blue"};

class Brdf {
 public:
  virtual ~Brdf() = default;

  // l: towards the light, v: towards the viewer, n: surface normal; all unit length.
  // Returns 0 when l or v is below the surface (n·l <= 0 or n·v <= 0).
  virtual Rgb Eval(const Vec3& l, const Vec3& v, const Vec3& n) const = 0;

  // Short human-readable description, e.g. "ggx(alpha=0.2)".
  virtual std::string Name() const = 0;
};

}  // namespace brdfrig::brdf
