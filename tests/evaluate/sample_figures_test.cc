#include "evaluate/sample_figures.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/srgb.h"
#include "evaluate/material_report.h"

namespace brdfrig::evaluate {
namespace {

cv::Mat Constant(float value) { return cv::Mat(8, 8, CV_32FC3, cv::Scalar::all(value)); }
cv::Mat AllSample() { return cv::Mat(8, 8, CV_8UC1, cv::Scalar(255)); }

TEST(SampleFigures, NormalizedFigureIsDefinedWhereTheReferenceIsLit) {
  const SampleFigures f =
      CompareSampleRadiance(Constant(0.5f), Constant(0.55f), AllSample(), "truth");
  EXPECT_DOUBLE_EQ(f.peak, 0.5);
  // Both divided by 0.5: 1 against 1.1, clamped to 1: the same pixels.
  EXPECT_TRUE(std::isinf(f.normalized_sample.psnr_db));
  const SampleFigures darker =
      CompareSampleRadiance(Constant(0.5f), Constant(0.25f), AllSample(), "truth");
  EXPECT_NEAR(darker.normalized_sample.psnr_db, 20 * std::log10(1 / (1 - SrgbEncode(0.5))), 1e-3);
}

TEST(SampleFigures, BlackReferenceHasNoNormalizedFigure) {
  // A mirror seen away from its highlight: nothing to normalize by, whether the fit is black
  // too (which used to read +inf dB) or not (a figure on an arbitrary scale).
  EXPECT_TRUE(std::isnan(CompareSampleRadiance(Constant(0), Constant(0), AllSample(), "truth")
                             .normalized_sample.psnr_db));
  const SampleFigures bright =
      CompareSampleRadiance(Constant(0), Constant(0.3f), AllSample(), "truth");
  EXPECT_TRUE(std::isnan(bright.normalized_sample.psnr_db));
  EXPECT_GT(bright.relative_rmse, 0);  // the absolute error is still reported
}

TEST(SampleFigures, MeanOfDefinedLeavesUndefinedOut) {
  const DefinedMean m = MeanOfDefined({30, NAN, 40});
  EXPECT_DOUBLE_EQ(m.mean, 35);
  EXPECT_EQ(m.count, 2);
  const DefinedMean none = MeanOfDefined({NAN, NAN});
  EXPECT_TRUE(std::isnan(none.mean));
  EXPECT_EQ(none.count, 0);
}

TEST(SampleFigures, ElevationSummaryLeavesBlackViewsOutOfTheNormalizedMean) {
  std::vector<HeldOutResult> views(3);
  const double psnr[] = {30, NAN, 34};
  for (int i = 0; i < 3; ++i) {
    views[i].view.elevation = 75 * M_PI / 180;
    views[i].normalized_sample.psnr_db = psnr[i];
  }
  const std::vector<ElevationSummary> s = SummarizeByElevation(views);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].views, 3);
  EXPECT_EQ(s[0].normalized_views, 2);
  EXPECT_DOUBLE_EQ(s[0].normalized_sample_psnr_db, 32);
}

}  // namespace
}  // namespace brdfrig::evaluate
