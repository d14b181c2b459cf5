// The bracket merge on a dark surface: read noise clipped at zero (a linear photo written
// without a black level) must not turn a dark surface bright. The longest exposure's dark values,
// zeros included, are its measurement; the noise floor says where that measurement ends.
#include "reconstruct/hdr_merge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/error.h"

namespace brdfrig::reconstruct {
namespace {

constexpr double kReadNoise = 5e-4;  // full scale, as the simulated 14-bit sensor
const std::vector<double> kExposures = {0.001, 0.008, 0.0666667};

// A bracket of a uniform surface of `radiance` (full scale per second): each exposure's value
// with Gaussian read noise, clipped to [0, 1] and written as 16-bit codes.
std::vector<cv::Mat> Bracket(double radiance, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, kReadNoise);
  std::vector<cv::Mat> out;
  for (double t : kExposures) {
    cv::Mat image(64, 64, CV_16UC3);
    for (auto it = image.begin<cv::Vec3w>(); it != image.end<cv::Vec3w>(); ++it) {
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp(radiance * t + noise(rng), 0.0, 1.0);
        (*it)[c] = static_cast<ushort>(std::lround(v * 65535));
      }
    }
    out.push_back(image);
  }
  return out;
}

double MeanRadiance(const HdrImage& hdr) {
  const cv::Scalar mean = cv::mean(hdr.radiance);
  return (mean[0] + mean[1] + mean[2]) / 3;
}

TEST(HdrMergeTest, ADarkSurfaceAtTheNoiseFloorMergesToItsTrueMean) {
  const HdrMergeOptions options;
  // Twice the read noise in the longest exposure: the clipped noise of every exposure adds about
  // 2 % (the old merge, which dropped values at or below 1e-4, read 35 % high).
  const double truth = options.noise_floor / kExposures.back();
  const HdrImage hdr = MergeBracket(Bracket(truth, 1), kExposures, {}, options);
  EXPECT_NEAR(MeanRadiance(hdr) / truth, 1.0, 0.03);
  EXPECT_DOUBLE_EQ(hdr.noise_floor, truth);
  EXPECT_EQ(hdr.invalid_fraction, 0);
}

TEST(HdrMergeTest, ABlackSurfaceStaysBelowTheNoiseFloor) {
  // Only the clipped noise's own mean (about 0.44 σ in the longest exposure) is left. The old
  // merge dropped the zeros and left a shorter exposure's positive noise: 11 σ.
  const HdrImage hdr = MergeBracket(Bracket(0, 2), kExposures, {}, {});
  const double floor_level = hdr.noise_floor * kExposures.back();  // full scale
  EXPECT_LT(MeanRadiance(hdr) * kExposures.back(), 0.5 * kReadNoise);
  EXPECT_LT(MeanRadiance(hdr) * kExposures.back(), 0.5 * floor_level);
}

TEST(HdrMergeTest, TheNoiseFloorOptionIsChecked) {
  HdrMergeOptions options;
  options.noise_floor = -1;
  EXPECT_THROW(options.Validate(), OptionsError);
  options.noise_floor = 1;
  EXPECT_THROW(options.Validate(), OptionsError);
}

}  // namespace
}  // namespace brdfrig::reconstruct
