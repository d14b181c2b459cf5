#include "evaluate/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>

namespace brdfrig::evaluate {
namespace {

TEST(SvgPlotTest, DrawsOnePolylinePerSeriesAndEscapesLabels) {
  Series a{"1 photo <a&b>", {0, 1, 2}, {40, 45, 50}};
  Series b{"6 photos", {0, 1, 2}, {48, NAN, 52}};
  const std::string svg = SvgLinePlot({a, b}, {"PSNR", "phi", "dB"});
  std::size_t count = 0;
  for (std::size_t p = svg.find("<polyline"); p != std::string::npos;
       p = svg.find("<polyline", p + 1)) {
    ++count;
  }
  EXPECT_EQ(count, 2u);
  EXPECT_NE(svg.find("1 photo &lt;a&amp;b&gt;"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(SvgPlotTest, EmptyInputStillGivesAValidDocument) {
  const std::string svg = SvgLinePlot({}, {"empty", "x", "y"});
  EXPECT_EQ(svg.rfind("</svg>"), svg.size() - 7);
}

}  // namespace
}  // namespace brdfrig::evaluate
