// Angle units. Angles are radians in code and in files; degrees appear only in what people read
// or write (UI text, reports, the `_deg` keys of YAML files). These two are the only conversions.
#pragma once

#include <cmath>

namespace brdfrig {

constexpr double Radians(double degrees) { return degrees * (M_PI / 180.0); }
constexpr double Degrees(double radians) { return radians * (180.0 / M_PI); }

}  // namespace brdfrig
