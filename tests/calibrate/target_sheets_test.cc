// The printed sheets: the board drawn as vectors is OpenCV's own board, each sheet declares its
// physical size, the scale bar is as long as it says, and impossible boards are refused.
#include "calibrate/target_sheets.h"

#include <gtest/gtest.h>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>

#include "common/error.h"

namespace brdfrig::calibrate {
namespace {

TEST(TargetSheetsTest, RasterizedBoardMatchesOpenCvsOwnDrawingOfTheBoard) {
  const CharucoSpec spec;         // 11 x 8 squares of 20 mm
  const double px_per_m = 10000;  // 10 px/mm: the board's squares are 200 px
  const cv::Mat sheet = RasterizeCharucoSheet(spec, px_per_m);
  const Eigen::Vector2d origin = spec.OriginOnPage() * px_per_m;
  const cv::Rect board_area(static_cast<int>(std::lround(origin.x())),
                            static_cast<int>(std::lround(origin.y())),
                            static_cast<int>(std::lround(spec.BoardWidth() * px_per_m)),
                            static_cast<int>(std::lround(spec.BoardHeight() * px_per_m)));
  cv::Mat ours = 255 - sheet(board_area);  // ink → black, as OpenCV draws it
  cv::Mat theirs;
  spec.MakeBoard()->draw(board_area.size(), theirs, 0, 1);
  cv::Mat differs;
  cv::compare(cv::abs(ours - theirs) + cv::abs(theirs - ours), 128, differs, cv::CMP_GT);
  // OpenCV draws marker cells on whole pixels, so edges may disagree by a pixel; a misplaced
  // square or cell would leave a blob of disagreement that survives erosion by 3 x 3.
  cv::Mat blobs;
  cv::erode(differs, blobs, cv::Mat::ones(3, 3, CV_8U));
  EXPECT_EQ(cv::countNonZero(blobs), 0) << cv::countNonZero(differs) << " edge pixels differ";
  EXPECT_LT(cv::countNonZero(differs), 0.01 * board_area.area());
  // The page outside the board (without the scale) is bare paper.
  cv::Mat outside = sheet.clone();
  outside(board_area).setTo(0);
  EXPECT_EQ(cv::countNonZero(outside), 0);
}

TEST(TargetSheetsTest, SvgAndPdfDeclareTheExactPageSize) {
  const CharucoSpec spec;
  const std::string svg = CharucoSheet(spec, SheetFormat::kSvg);
  EXPECT_NE(svg.find("width=\"297mm\""), std::string::npos) << svg.substr(0, 400);
  EXPECT_NE(svg.find("height=\"210mm\""), std::string::npos) << svg.substr(0, 400);
  const std::string pdf = CharucoSheet(spec, SheetFormat::kPdf);
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(pdf, m, std::regex(R"(/MediaBox \[\s*0 0 ([0-9.]+) ([0-9.]+)\s*\])")))
      << "no MediaBox in the PDF";
  EXPECT_NEAR(std::stod(m[1]) * 25.4 / 72, 297.0, 0.01);
  EXPECT_NEAR(std::stod(m[2]) * 25.4 / 72, 210.0, 0.01);
}

TEST(TargetSheetsTest, ScaleBarIsAsLongAsItSaysInTenMillimetreSegments) {
  const CharucoSpec spec;
  const double px_per_m = 10000;
  const cv::Mat sheet = RasterizeCharucoSheet(spec, px_per_m, true);
  // The bar's middle row: 6 mm into the scale strip, 1 mm down into the 2 mm bar.
  const int row = static_cast<int>((spec.page_height_m - kScaleStripM + 0.007) * px_per_m);
  std::vector<std::pair<int, int>> runs;  // [first, last] inked columns of each black segment
  for (int x = 0; x < sheet.cols; ++x) {
    const bool ink = sheet.at<std::uint8_t>(row, x) > 128;
    if (ink && (runs.empty() || runs.back().second != x - 1)) runs.push_back({x, x});
    if (ink) runs.back().second = x;
  }
  ASSERT_EQ(ScaleBarLength(spec.page_width_m), 0.1);
  // 10 segments, every other one black; the outline adds a hairline to the last white one.
  ASSERT_GE(runs.size(), 5u);
  const double mm = px_per_m * 1e-3;
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR((runs[i].second - runs[i].first + 1) / mm, 10.0, 0.2) << "segment " << i;
    if (i > 0) {
      EXPECT_NEAR((runs[i].first - runs[i - 1].first) / mm, 20.0, 0.25);  // outline's pixel
    }
  }
  EXPECT_NEAR((runs.back().second + 1 - runs.front().first) / mm, 100.0, 0.3);
}

TEST(TargetSheetsTest, ImpossibleBoardsAreRefusedNamingTheField) {
  CharucoSpec markers_too_big;
  markers_too_big.marker_m = 0.02;
  EXPECT_THROW(markers_too_big.Validate(), OptionsError);
  CharucoSpec too_many_markers;
  too_many_markers.squares_x = 16;
  too_many_markers.squares_y = 16;  // 128 markers, DICT_5X5_100 holds 100
  try {
    too_many_markers.Validate();
    FAIL() << "expected an error";
  } catch (const OptionsError& e) {
    EXPECT_NE(std::string(e.what()).find("DICT_5X5_100"), std::string::npos) << e.what();
  }
  CharucoSpec page_too_small;
  page_too_small.page_width_m = 0.2;
  EXPECT_THROW(page_too_small.Validate(), OptionsError);
  CharucoSpec unknown_dictionary;
  unknown_dictionary.dictionary = "DICT_3X3_9";
  EXPECT_THROW(unknown_dictionary.Validate(), OptionsError);
}

}  // namespace
}  // namespace brdfrig::calibrate
