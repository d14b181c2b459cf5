#include "evaluate/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"

namespace brdfrig::evaluate {
namespace {

TEST(PsnrTest, MatchesClosedFormForConstantError) {
  cv::Mat a(10, 20, CV_16UC3, cv::Scalar::all(1000));
  cv::Mat b(10, 20, CV_16UC3, cv::Scalar::all(1010));
  const PsnrResult r = Psnr(a, b, cv::Mat(), 4095, "test");
  EXPECT_NEAR(r.rmse, 10, 1e-12);
  EXPECT_NEAR(r.psnr_db, 20 * std::log10(4095.0 / 10), 1e-9);
  EXPECT_EQ(r.pixels, 200);
}

TEST(PsnrTest, MaskRestrictsTheRegion) {
  cv::Mat a(4, 4, CV_32FC1, cv::Scalar(0)), b = a.clone();
  b.at<float>(0, 0) = 100;  // error only outside the mask
  cv::Mat mask(4, 4, CV_8UC1, cv::Scalar(0));
  mask.at<uchar>(3, 3) = 1;
  EXPECT_TRUE(std::isinf(Psnr(a, b, mask, 1, "masked").psnr_db));
  EXPECT_TRUE(std::isfinite(Psnr(a, b, cv::Mat(), 1, "whole").psnr_db));
}

TEST(PsnrTest, MismatchedOrEmptyInputsAreErrors) {
  cv::Mat a(4, 4, CV_32FC1, cv::Scalar(0));
  EXPECT_THROW(Psnr(a, cv::Mat(5, 4, CV_32FC1), cv::Mat(), 1, "x"), Error);
  EXPECT_THROW(Psnr(a, a, cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)), 1, "x"), Error);
  EXPECT_THROW(Psnr(a, a, cv::Mat(), 0, "x"), Error);
}

}  // namespace
}  // namespace brdfrig::evaluate
