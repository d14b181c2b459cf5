// The printable sheets: a ChArUco board and a marker mask drawn as vectors at exact physical
// size (PDF and SVG through cairo), each stating its own scale (a title with the square or
// marker size, and a bar of stated length in alternating 10 mm segments) so a print can be
// checked with a ruler. The same drawing rasterized is the board the simulator photographs.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "calibrate/charuco_spec.h"
#include "calibrate/marker_mask.h"

namespace brdfrig::calibrate {

enum class SheetFormat { kPdf, kSvg };

// The sheet's file content (one page of the spec's page size).
std::string CharucoSheet(const CharucoSpec& spec, SheetFormat format);
std::string MaskSheet(const MarkerMaskSpec& spec, SheetFormat format);

// Length of the scale bar printed on a page of this width (metres): 100 mm where it fits.
double ScaleBarLength(double page_width_m);

// The sheets rasterized at `px_per_m` with the same drawing: CV_8U, the page's size, 255 where
// ink covers a pixel fully, 0 on bare paper (anti-aliased in between). Pixel (u, v) covers page
// coordinates [u, u + 1) / px_per_m from the page's top-left. The board's title and scale bar
// only with `with_scale` (text depends on the system's fonts; the simulator leaves it out).
cv::Mat RasterizeCharucoSheet(const CharucoSpec& spec, double px_per_m, bool with_scale = false);
// The mask without its texts (its markers, cut line and scale bar).
cv::Mat RasterizeMaskSheet(const MarkerMaskSpec& spec, double px_per_m);

}  // namespace brdfrig::calibrate
