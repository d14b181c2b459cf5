#include "sim/sheet_print.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "calibrate/marker_mask.h"
#include "calibrate/target_sheets.h"

namespace brdfrig::sim {

SheetPrint::SheetPrint(cv::Mat ink, double px_per_m, double width_m, double height_m,
                       double paper_albedo, double ink_albedo)
    : ink_(std::move(ink)),
      px_per_m_(px_per_m),
      width_m_(width_m),
      height_m_(height_m),
      paper_(paper_albedo),
      ink_albedo_(ink_albedo) {}

double SheetPrint::Coverage(double x, double y) const {
  // Bilinear between sample centres (sample (i, j) covers [i, i + 1) / px_per_m).
  const double u = x * px_per_m_ - 0.5, v = y * px_per_m_ - 0.5;
  const int i = std::clamp(static_cast<int>(std::floor(u)), 0, ink_.cols - 2);
  const int j = std::clamp(static_cast<int>(std::floor(v)), 0, ink_.rows - 2);
  const double fu = std::clamp(u - i, 0.0, 1.0), fv = std::clamp(v - j, 0.0, 1.0);
  const std::uint8_t* row0 = ink_.ptr<std::uint8_t>(j);
  const std::uint8_t* row1 = ink_.ptr<std::uint8_t>(j + 1);
  const double top = row0[i] * (1 - fu) + row0[i + 1] * fu;
  const double bottom = row1[i] * (1 - fu) + row1[i + 1] * fu;
  return (top * (1 - fv) + bottom * fv) / 255.0;
}

double SheetPrint::Albedo(double x, double y) const {
  return paper_ + (ink_albedo_ - paper_) * Coverage(x, y);
}

bool SheetPrint::Ink(double x, double y) const { return Coverage(x, y) >= 0.5; }

SheetPrint PrintOfMask(const geometry::TargetGeometry& target) {
  return SheetPrint(
      calibrate::RasterizeMaskSheet(calibrate::MarkerMaskSpec::ForTarget(target), kPrintPxPerM),
      kPrintPxPerM, target.paper_width, target.paper_height, target.paper_albedo, kTonerAlbedo);
}

}  // namespace brdfrig::sim
