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

TEST(SvgPlotTest, LogAxisTicksAtDecadesAndSkipsValuesItCannotShow) {
  Series peak{"peak", {0, 1, 2, 3}, {1e-3, 0, 1e2, -1}};
  PlotOptions options{"BRDF", "theta", "f", 640, 400, true};
  const std::string svg = SvgLinePlot({peak}, options);
  for (const char* tick : {">0.001<", ">0.01<", ">0.1<", ">1<", ">10<", ">100<"}) {
    EXPECT_NE(svg.find(tick), std::string::npos) << tick;
  }
  EXPECT_NE(svg.find("f (log scale)"), std::string::npos);
  // Two of the four points have a place on a log axis: two dots, one polyline of two points.
  std::size_t dots = 0;
  for (std::size_t p = svg.find("<circle"); p != std::string::npos;
       p = svg.find("<circle", p + 1)) {
    ++dots;
  }
  EXPECT_EQ(dots, 2u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(SvgPlotTest, EmptyInputStillGivesAValidDocument) {
  const std::string svg = SvgLinePlot({}, {"empty", "x", "y"});
  EXPECT_EQ(svg.rfind("</svg>"), svg.size() - 7);
}

}  // namespace
}  // namespace brdfrig::evaluate
