// Minimal line/scatter plots written as standalone SVG, so reports need no plotting library
// and open in any browser.
#pragma once

#include <string>
#include <vector>

namespace brdfrig::evaluate {

struct Series {
  std::string label;
  std::vector<double> x, y;  // same length; non-finite points are skipped
  bool lines = true;         // connect points (else markers only)
};

struct PlotOptions {
  std::string title, x_label, y_label;
  int width = 640, height = 400;
};

std::string SvgLinePlot(const std::vector<Series>& series, const PlotOptions& options);

}  // namespace brdfrig::evaluate
