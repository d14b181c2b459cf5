#include "evaluate/report.h"

#include <gtest/gtest.h>

#include <cmath>

namespace brdfrig::evaluate {
namespace {

Report Example() {
  Report r{"Demo <report>", {}};
  ReportSection s{"PSNR", {"whole photo & sample only"}, {}, {"<svg></svg>"}, {{"a.png", "photo"}}};
  s.tables.push_back({"Held-out views", {"view", "PSNR"}, {{"phi=0", "49.10"}, {"phi=15", "n/a"}}});
  r.sections.push_back(s);
  return r;
}

TEST(ReportTest, HtmlEscapesTextAndEmbedsPlotsAndImages) {
  const std::string html = Example().Html();
  EXPECT_NE(html.find("Demo &lt;report&gt;"), std::string::npos);
  EXPECT_NE(html.find("whole photo &amp; sample only"), std::string::npos);
  EXPECT_NE(html.find("<svg></svg>"), std::string::npos);
  EXPECT_NE(html.find("<img src='a.png'>"), std::string::npos);
  EXPECT_NE(html.find("<td>49.10</td>"), std::string::npos);
}

TEST(ReportTest, TextAlignsTableColumns) {
  const std::string text = Example().Text();
  EXPECT_NE(text.find("\n  view   PSNR\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n phi=0  49.10\nphi=15    n/a\n"), std::string::npos) << text;
}

TEST(ReportTest, FixedFormatsNonFiniteValues) {
  EXPECT_EQ(Fixed(1.23456, 2), "1.23");
  EXPECT_EQ(Fixed(INFINITY, 2), "inf");
  EXPECT_EQ(Fixed(NAN, 2), "n/a");
}

}  // namespace
}  // namespace brdfrig::evaluate
