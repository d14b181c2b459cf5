// Shutter-speed labels as cameras offer them through libgphoto2 config widgets, and the
// choice of the nearest one. Makers write them differently: Canon "1/60", "0.3", "30";
// Nikon "1/60", "30", sometimes "0.0166s"; Sony "1/60", "0.3\"", "30\"" and "1\"3" for 1.3 s.
// Non-times ("bulb", "Bulb", "auto", "x 200") are skipped.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brdfrig::rig {

// Seconds for a camera's label, or nullopt when the label is not a time.
std::optional<double> ParseShutterSpeed(std::string_view label);

// Index of the label nearest to `seconds` in stops (log2 ratio), or -1 when no label is a time.
int NearestShutterSpeed(const std::vector<std::string>& labels, double seconds);

// A person's exposure ("1/60", "0.5", "2s"): seconds, or throws OptionsError saying why.
double ParseExposureText(const std::string& text);

}  // namespace brdfrig::rig
