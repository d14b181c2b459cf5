// A tangent frame about a normal, for turning directions into the frame a table or network is
// indexed in.
#pragma once

#include <cmath>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

// An orthonormal frame (t, b, n) with n as its z axis (Duff et al.'s branchless construction).
// The materials are isotropic, so which tangent is chosen does not matter.
inline void OrthonormalFrame(const Vec3& n, Vec3* t, Vec3* b) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double c = n.x() * n.y() * a;
  *t = Vec3(1 + sign * n.x() * n.x() * a, sign * c, -sign * n.x());
  *b = Vec3(c, sign + n.y() * n.y() * a, -n.y());
}

}  // namespace brdfrig::brdf
