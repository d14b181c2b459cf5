// The check every downloaded frame passes before it is recorded: it decodes, has the size
// the rig's camera is expected to give, is not all black (lens cap, shutter failure), and how
// much of it is saturated (reported with the frame, and used by auto-bracketing).
#pragma once

#include <opencv2/core.hpp>
#include <span>
#include <string>

namespace brdfrig::acquire {

struct FrameCheckOptions {
  int expected_width = 0;  // 0 = do not check
  int expected_height = 0;
  double saturation_level = 0.98;  // fraction of full scale counted as saturated
  double black_level = 0.002;      // a frame whose brightest pixel is below this is "all black"
};

struct FrameCheck {
  bool decoded = false;  // false for formats not decoded here (RAW): then nothing is checked
  int width = 0, height = 0;
  double max_level = 0;           // brightest pixel, fraction of full scale
  double saturated_fraction = 0;  // pixels (any channel) at or above saturation_level
  bool ok = true;
  std::string problem;  // why not ok
};

// `levels`, when given, receives the decoded image as one float channel (max over colour
// channels) in fractions of full scale.
FrameCheck CheckFrame(std::span<const std::byte> bytes, const std::string& file_name,
                      const FrameCheckOptions& options, cv::Mat* levels = nullptr);

}  // namespace brdfrig::acquire
