// Number formatting for reports, tables and diagnostics.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace brdfrig {

// Fixed decimals; "inf"/"-inf"/"n/a" for non-finite values (a table never shows "nan").
inline std::string Fixed(double value, int decimals) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (!std::isfinite(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  return buffer;
}

// printf-style text, for numbers inside a sentence ("reprojection RMS %.3f px"); at most 255
// characters.
template <typename... Args>
std::string Printf(const char* format, Args... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), format, args...);
  return buffer;
}

// A device code as people read it in manuals: 0x42.
inline std::string Hex(int code) {
  char buffer[16];
  std::snprintf(buffer, sizeof(buffer), "0x%02X", code);
  return buffer;
}

}  // namespace brdfrig
