// Minimal line/scatter plots written as standalone SVG, so reports need no plotting library
// and open in any browser.
#pragma once

#include <string>
#include <vector>

namespace brdfrig::evaluate {

struct Series {
  std::string label;
  std::vector<double> x, y;  // same length; non-finite points (and y <= 0 on a log axis) skipped
  bool lines = true;         // connect points (else markers only)
  std::string colour;        // CSS colour; empty = the palette's next one
  bool dashed = false;       // a dashed line (a second model beside a solid one)
  bool markers = true;       // a dot at every point (lines only: false draws the bare curve)
};

struct PlotOptions {
  std::string title, x_label, y_label;
  int width = 640, height = 400;
  // A logarithmic y axis (ticks at the decades): BRDF values span orders of magnitude between
  // the specular peak and the diffuse floor, and a linear axis shows only the peak.
  bool log_y = false;
  // Fixed x ticks (ascending; the axis spans the first to the last): angles read best at round
  // steps such as every 30°. Empty = the data's range, padded, with round ticks.
  std::vector<double> x_ticks;
};

std::string SvgLinePlot(const std::vector<Series>& series, const PlotOptions& options);

}  // namespace brdfrig::evaluate
