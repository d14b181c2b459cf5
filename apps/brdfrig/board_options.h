// The ChArUco board's command-line options, shared by `target print` and `rig calibrate lens`
// so both name the board alike: --board targets.json (what `target print` wrote) or the
// individual sizes (e.g. the square size measured on the print with a ruler).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "calibrate/charuco_spec.h"

namespace brdfrig::apps {

struct BoardArgs {
  std::string board_file;
  std::vector<int> squares;
  double square_mm = 0, marker_mm = 0;
  std::string dictionary;
  std::vector<double> page_mm;
};

void AddBoardOptions(CLI::App* cmd, BoardArgs& args, bool with_file);
// The defaults of calibrate::CharucoSpec, then the file, then the flags given.
calibrate::CharucoSpec BoardSpecFrom(const BoardArgs& args);

}  // namespace brdfrig::apps
