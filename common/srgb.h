// The sRGB transfer function (IEC 61966-2-1), the one encoding every display image, JPEG and
// display-space figure in the project uses.
#pragma once

#include <algorithm>
#include <cmath>

namespace brdfrig {

// Linear [0, 1] to the sRGB code value [0, 1]; the input is clamped to [0, 1] first.
inline double SrgbEncode(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

}  // namespace brdfrig
