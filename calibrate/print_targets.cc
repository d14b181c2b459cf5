#include "calibrate/print_targets.h"

#include <nlohmann/json.hpp>
#include <sstream>

#include "calibrate/target_sheets.h"
#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig::calibrate {

void PrintTargetsOptions::Validate() const {
  if (output_dir.empty()) throw OptionsError("PrintTargetsOptions.output_dir: required");
  board.Validate();
  mask.Validate();
}

std::string PrintTargetsSummary::ToString() const {
  std::ostringstream out;
  out << "wrote a ChArUco board (" << board_corners << " inner corners) and a marker mask ("
      << mask_markers << " markers):";
  for (const auto& f : files) out << "\n  " << f.string();
  out << "\nprint at 100 % (no fit to page) and check the scale bar with a ruler";
  return out.str();
}

PrintTargetsSummary PrintTargets(const PrintTargetsOptions& options) {
  options.Validate();
  CreateDirectories(options.output_dir);
  PrintTargetsSummary summary;
  auto write = [&](const std::string& name, const std::string& content) {
    const std::filesystem::path path = options.output_dir / name;
    WriteFileAtomically(path, content);
    summary.files.push_back(path);
  };
  write("charuco_board.pdf", CharucoSheet(options.board, SheetFormat::kPdf));
  write("charuco_board.svg", CharucoSheet(options.board, SheetFormat::kSvg));
  write("marker_mask.pdf", MaskSheet(options.mask, SheetFormat::kPdf));
  write("marker_mask.svg", MaskSheet(options.mask, SheetFormat::kSvg));

  const std::vector<MaskMarker> markers = MaskMarkers(options.mask);
  nlohmann::json corners = nlohmann::json::array();
  for (const MaskMarker& m : markers) {
    nlohmann::json c = nlohmann::json::array();
    for (const Eigen::Vector2d& p : m.corners) c.push_back({p.x(), p.y()});
    corners.push_back({{"id", m.id}, {"corners_m", c}});
  }
  nlohmann::json mask = options.mask.ToJson();
  mask["markers"] = corners;
  mask["coordinates"] =
      "sample plane, cut-out centred at the origin, x = world +x, y = world +y (top of the "
      "page); corners top-left, top-right, bottom-right, bottom-left as printed";
  const nlohmann::json targets = {{"format", "brdfrig-targets"},
                                  {"version", 1},
                                  {"board", options.board.ToJson()},
                                  {"mask", mask}};
  write("targets.json", targets.dump(2) + "\n");
  summary.board_corners = options.board.InnerCorners();
  summary.mask_markers = static_cast<int>(markers.size());
  return summary;
}

}  // namespace brdfrig::calibrate
