#include "evaluate/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <tuple>
#include <vector>

namespace brdfrig::evaluate {
namespace {

constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                    "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string Escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Range padded by 5 % (or ±1 around a single value).
std::pair<double, double> Padded(double lo, double hi) {
  if (!(lo < hi)) return {lo - 1, hi + 1};
  const double pad = 0.05 * (hi - lo);
  return {lo - pad, hi + pad};
}

// Ticks at round values (1, 2 or 5 times a power of ten) inside [lo, hi], about `count` of
// them: axis labels a person reads at a glance, not the padded range's fifths.
std::vector<double> NiceTicks(double lo, double hi, int count) {
  const double raw = (hi - lo) / count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

std::string Label(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

}  // namespace

std::string SvgLinePlot(const std::vector<Series>& series, const PlotOptions& options) {
  // On a log axis every y is drawn at log10(y); values <= 0 have no place there.
  auto plotted_y = [&](double y) {
    if (!options.log_y) return y;
    return y > 0 ? std::log10(y) : std::numeric_limits<double>::quiet_NaN();
  };
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
  for (const Series& s : series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      const double y = plotted_y(s.y[i]);
      if (!std::isfinite(s.x[i]) || !std::isfinite(y)) continue;
      x_lo = std::min(x_lo, s.x[i]);
      x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, y);
      y_hi = std::max(y_hi, y);
    }
  }
  if (!std::isfinite(x_lo)) x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;
  std::tie(x_lo, x_hi) = Padded(x_lo, x_hi);
  const bool fixed_x =
      options.x_ticks.size() >= 2 && options.x_ticks.front() < options.x_ticks.back();
  if (fixed_x) x_lo = options.x_ticks.front(), x_hi = options.x_ticks.back();
  std::tie(y_lo, y_hi) = Padded(y_lo, y_hi);

  const double left = 70, right = 160, top = 40, bottom = 50;
  const double pw = options.width - left - right, ph = options.height - top - bottom;
  auto sx = [&](double x) { return left + (x - x_lo) / (x_hi - x_lo) * pw; };
  auto sy = [&](double y) { return top + (1 - (y - y_lo) / (y_hi - y_lo)) * ph; };

  std::ostringstream svg;
  svg.precision(4);
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << options.width << "' height='"
      << options.height << "' font-family='sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << options.width / 2 << "' y='20' text-anchor='middle' font-size='14'>"
      << Escape(options.title) << "</text>\n"
      << "<rect x='" << left << "' y='" << top << "' width='" << pw << "' height='" << ph
      << "' fill='none' stroke='black'/>\n";
  for (const double xv : fixed_x ? options.x_ticks : NiceTicks(x_lo, x_hi, 6)) {
    svg << "<line x1='" << sx(xv) << "' y1='" << top + ph << "' x2='" << sx(xv) << "' y2='"
        << top + ph + 5 << "' stroke='black'/><text x='" << sx(xv) << "' y='" << top + ph + 18
        << "' text-anchor='middle'>" << Label(xv) << "</text>\n";
  }
  std::vector<double> y_ticks;  // in plotted units
  const int first_decade = static_cast<int>(std::ceil(y_lo)),
            last_decade = static_cast<int>(std::floor(y_hi));
  if (options.log_y && last_decade - first_decade >= 1) {
    const int step = std::max(1, (last_decade - first_decade + 7) / 8);  // at most ~8 labels
    for (int d = first_decade; d <= last_decade; d += step) y_ticks.push_back(d);
  } else if (options.log_y) {
    for (int i = 0; i <= 5; ++i) y_ticks.push_back(y_lo + (y_hi - y_lo) * i / 5);
  } else {
    y_ticks = NiceTicks(y_lo, y_hi, 6);
  }
  for (const double yv : y_ticks) {
    const std::string label = options.log_y ? Label(std::pow(10.0, yv)) : Label(yv);
    svg << "<line x1='" << left - 5 << "' y1='" << sy(yv) << "' x2='" << left << "' y2='" << sy(yv)
        << "' stroke='black'/><text x='" << left - 8 << "' y='" << sy(yv) + 4
        << "' text-anchor='end'>" << label << "</text>\n";
    if (options.log_y) {
      svg << "<line x1='" << left << "' y1='" << sy(yv) << "' x2='" << left + pw << "' y2='"
          << sy(yv) << "' stroke='#ddd'/>\n";
    }
  }
  svg << "<text x='" << left + pw / 2 << "' y='" << options.height - 10 << "' text-anchor='middle'>"
      << Escape(options.x_label) << "</text>\n"
      << "<text transform='translate(15," << top + ph / 2 << ") rotate(-90)' text-anchor='middle'>"
      << Escape(options.y_label + (options.log_y ? " (log scale)" : "")) << "</text>\n";
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    const std::string colour =
        s.colour.empty() ? kColours[k % std::size(kColours)] : Escape(s.colour);
    std::ostringstream points;
    points.precision(5);
    svg << "<g class='series' data-label='" << Escape(s.label) << "'>\n";
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      const double y = plotted_y(s.y[i]);
      if (!std::isfinite(s.x[i]) || !std::isfinite(y) || s.x[i] < x_lo || s.x[i] > x_hi) continue;
      points << sx(s.x[i]) << "," << sy(y) << " ";
      if (s.markers || !s.lines) {
        svg << "<circle cx='" << sx(s.x[i]) << "' cy='" << sy(y) << "' r='" << (s.lines ? 3 : 2)
            << "' fill='" << colour << "'" << (s.lines ? "" : " fill-opacity='0.5'") << "/>\n";
      }
    }
    if (s.lines) {
      svg << "<polyline fill='none' stroke='" << colour << "' stroke-width='1.5'"
          << (s.dashed ? " stroke-dasharray='6,4'" : "") << " points='" << points.str() << "'/>\n";
    }
    svg << "</g>\n";
    const double ly = top + 10 + 18 * static_cast<double>(k);
    if (s.lines) {
      svg << "<line x1='" << left + pw + 8 << "' y1='" << ly - 4 << "' x2='" << left + pw + 26
          << "' y2='" << ly - 4 << "' stroke='" << colour << "' stroke-width='2'"
          << (s.dashed ? " stroke-dasharray='5,3'" : "") << "/>";
    } else {
      svg << "<circle cx='" << left + pw + 17 << "' cy='" << ly - 4 << "' r='3' fill='" << colour
          << "'/>";
    }
    svg << "<text x='" << left + pw + 30 << "' y='" << ly << "'>" << Escape(s.label) << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace brdfrig::evaluate
