#include "rig/shutter_speed.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "common/error.h"

namespace brdfrig::rig {
namespace {

std::optional<double> ParseNumber(std::string_view text) {
  if (text.empty()) return std::nullopt;
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

std::optional<double> ParseShutterSpeed(std::string_view label) {
  std::string text;
  for (char c : label) {
    if (!std::isspace(static_cast<unsigned char>(c))) text.push_back(c);
  }
  // Trailing unit marks: "s" (Nikon "0.0166s"), '"' (Sony seconds, 30").
  while (!text.empty() && (text.back() == 's' || text.back() == '"')) text.pop_back();
  // Sony/Pentax write 1.3 s as 1"3.
  if (const auto quote = text.find('"'); quote != std::string::npos) text[quote] = '.';
  std::optional<double> seconds;
  if (const auto slash = text.find('/'); slash != std::string::npos) {
    const auto numerator = ParseNumber(std::string_view(text).substr(0, slash));
    const auto denominator = ParseNumber(std::string_view(text).substr(slash + 1));
    if (numerator && denominator && *denominator > 0) seconds = *numerator / *denominator;
  } else {
    seconds = ParseNumber(text);
  }
  if (!seconds || !(*seconds > 0) || !std::isfinite(*seconds)) return std::nullopt;
  return seconds;
}

int NearestShutterSpeed(const std::vector<std::string>& labels, double seconds) {
  int best = -1;
  double best_stops = INFINITY;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const auto value = ParseShutterSpeed(labels[i]);
    if (!value) continue;
    const double stops = std::abs(std::log2(*value / seconds));
    if (stops < best_stops - 1e-9) {
      best_stops = stops;
      best = static_cast<int>(i);
    }
  }
  return best;
}

double ParseExposureText(const std::string& text) {
  const auto seconds = ParseShutterSpeed(text);
  if (!seconds) {
    throw OptionsError("exposure '" + text + "': expected seconds such as 1/60, 0.5 or 2");
  }
  return *seconds;
}

}  // namespace brdfrig::rig
