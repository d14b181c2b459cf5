// The coverage map drawn as SVG: plain text, no dependency, readable in any browser and
// embeddable in docs and reports.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/angles.h"
#include "common/format.h"
#include "coverage/coverage.h"

namespace brdfrig::coverage {
namespace {

// Distinct hues for up to ten positions, then repeated (a plan is rarely longer).
const char* Colour(std::size_t i) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return kColours[i % 10];
}

}  // namespace

std::string CoverageSvg(const CoverageMap& map, const std::string& title) {
  const int nh = map.grid.theta_h_bins, nd = map.grid.theta_d_bins;
  const double left = 60, top = 40, size = 480, legend = 200;
  const double cw = size / nh, ch = size / nd;
  const double width = left + size + 20 + legend, height = top + size + 50;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<defs><pattern id=\"hatch\" width=\"6\" height=\"6\" patternUnits=\"userSpaceOnUse\" "
         "patternTransform=\"rotate(45)\"><rect width=\"6\" height=\"6\" fill=\"white\"/>"
         "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"6\" stroke=\"black\" stroke-width=\"2\"/>"
         "</pattern></defs>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << left << "\" y=\"20\" font-size=\"14\">" << title << " — covered "
      << Fixed(100 * map.covered_fraction, 1) << " %</text>\n"
      << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << size << "\" height=\"" << size
      << "\" fill=\"#f4f4f4\" stroke=\"black\"/>\n";
  // θd grows upwards: cell row r (from the bottom) is at y = top + size - (r + 1) · ch.
  for (std::size_t p = 0; p < map.positions.size(); ++p) {
    const PositionCoverage& c = map.positions[p];
    const std::string fill = c.validation ? "url(#hatch)" : Colour(p);
    svg << "<g fill=\"" << fill << "\" fill-opacity=\"" << (c.validation ? 0.6 : 0.7)
        << "\" stroke=\"" << Colour(p) << "\" stroke-width=\"0.5\">\n";
    for (const int cell : c.cells) {
      const int h = cell / nd, d = cell % nd;
      svg << "<rect x=\"" << Fixed(left + h * cw, 1) << "\" y=\""
          << Fixed(top + size - (d + 1) * ch, 1) << "\" width=\"" << Fixed(cw, 1) << "\" height=\""
          << Fixed(ch, 1) << "\"/>\n";
    }
    svg << "</g>\n";
  }
  // θh ticks at the warped positions of round angles.
  for (const double deg : {0.0, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 45.0, 60.0, 90.0}) {
    const double x = left + std::sqrt(deg / 90) * size;
    svg << "<line x1=\"" << Fixed(x, 1) << "\" y1=\"" << top + size << "\" x2=\"" << Fixed(x, 1)
        << "\" y2=\"" << top + size + 5 << "\" stroke=\"black\"/><text x=\"" << Fixed(x, 1)
        << "\" y=\"" << top + size + 18 << "\" text-anchor=\"middle\">" << deg << "</text>\n";
  }
  for (int deg = 0; deg <= 90; deg += 15) {
    const double y = top + size - deg / 90.0 * size;
    svg << "<line x1=\"" << left - 5 << "\" y1=\"" << Fixed(y, 1) << "\" x2=\"" << left
        << "\" y2=\"" << Fixed(y, 1) << "\" stroke=\"black\"/><text x=\"" << left - 8 << "\" y=\""
        << Fixed(y + 4, 1) << "\" text-anchor=\"end\">" << deg << "</text>\n";
  }
  svg << "<text x=\"" << left + size / 2 << "\" y=\"" << top + size + 38
      << "\" text-anchor=\"middle\">θh (degrees, sqrt axis)</text>\n"
      << "<text x=\"18\" y=\"" << top + size / 2
      << "\" text-anchor=\"middle\" transform=\"rotate(-90 18 " << top + size / 2
      << ")\">θd (degrees)</text>\n";
  for (std::size_t p = 0; p < map.positions.size(); ++p) {
    const PositionCoverage& c = map.positions[p];
    const double y = top + 10 + 34 * p;
    const double x = left + size + 20;
    svg << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"14\" height=\"14\" fill=\""
        << (c.validation ? "url(#hatch)" : Colour(p)) << "\" stroke=\"" << Colour(p) << "\"/>"
        << "<text x=\"" << x + 20 << "\" y=\"" << y + 11 << "\">" << p
        << (c.validation ? " (validation)" : "") << "</text>\n<text x=\"" << x + 20 << "\" y=\""
        << y + 25 << "\" font-size=\"10\">";
    std::string axes;
    for (const auto& [name, angle] : c.axes) {
      axes += (axes.empty() ? "" : " ") + name + "=" + Fixed(Degrees(angle), 1);
    }
    svg << axes << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace brdfrig::coverage
