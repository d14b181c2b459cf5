// Auto-bracketing from a metering shot: the shortest exposure keeps the highlight, the longest
// brings the paper to its level and the sample (the cut-out's median) above the reconstruction's
// noise floor, up to the longest exposure the plan allows.
#include "acquire/auto_bracket.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace brdfrig::acquire {
namespace {

geometry::RigGeometry Rig() {
  geometry::RigGeometry g;
  g.intrinsics = {400, 300, 400, 400, 200, 150};
  return g;
}

// A metering shot of the nominal geometry: paper at `paper`, the cut-out at `sample`, and one
// bright pixel (the highlight) at `highlight`.
cv::Mat MeteringShot(const geometry::RigGeometry& g, float paper, float sample, float highlight) {
  cv::Mat levels(g.intrinsics.height, g.intrinsics.width, CV_32F, cv::Scalar(paper));
  const geometry::CameraPose pose = g.CameraAt({});
  std::vector<cv::Point> corners;
  for (const auto& [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    Eigen::Vector2d pixel;
    EXPECT_TRUE(geometry::ProjectToPixel(
        g.intrinsics, pose,
        geometry::Vec3(0.5 * x * g.target.cutout_width, 0.5 * y * g.target.cutout_height, 0),
        &pixel));
    corners.emplace_back(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
  }
  cv::fillConvexPoly(levels, corners, cv::Scalar(sample));
  levels.at<float>(g.intrinsics.height / 2, g.intrinsics.width / 2) = highlight;
  return levels;
}

TEST(AutoBracketTest, ABrightSampleLeavesTheBracketToThePaperAndTheHighlight) {
  const geometry::RigGeometry g = Rig();
  const AutoBracket settings;  // paper 0.4, sample 0.01, highlight 0.8
  const MeteringResult m = ChooseBracket(MeteringShot(g, 0.1f, 0.05f, 0.9f), 0.01, g, {}, settings);
  ASSERT_EQ(m.bracket_s.size(), 3u);
  EXPECT_NEAR(m.paper_level, 0.1, 1e-6);
  EXPECT_NEAR(m.sample_level, 0.05, 1e-6);
  EXPECT_NEAR(m.bracket_s.front(), 0.01 * 0.8 / 0.9, 1e-9);  // the highlight at 0.8
  EXPECT_NEAR(m.bracket_s.back(), 0.01 * 0.4 / 0.1, 1e-9);   // the paper at 0.4
  EXPECT_FALSE(m.sample_needs_s);
}

TEST(AutoBracketTest, ADarkSampleLengthensTheLongestExposureUntilItReadsAboveTheFloor) {
  const geometry::RigGeometry g = Rig();
  const AutoBracket settings;
  // The paper would need 0.04 s; the sample, 2000 times darker than the paper, 2 s to reach
  // 1 % of full scale.
  const MeteringResult m = ChooseBracket(MeteringShot(g, 0.1f, 5e-5f, 0.5f), 0.01, g, {}, settings);
  ASSERT_EQ(m.bracket_s.size(), 3u);
  EXPECT_NEAR(m.sample_level, 5e-5, 1e-9);
  EXPECT_NEAR(m.bracket_s.back(), 0.01 * 0.01 / 5e-5, 1e-6);
  EXPECT_NEAR(m.bracket_s.front(), 0.016, 1e-9);  // the shortest still keeps the highlight
  // The middle exposure halfway in stops.
  EXPECT_NEAR(std::log(m.bracket_s[1]), 0.5 * (std::log(0.016) + std::log(2.0)), 1e-6);
  EXPECT_FALSE(m.sample_needs_s);
}

TEST(AutoBracketTest, ASampleTooDarkForTheLongestAllowedExposureStopsThereAndSaysWhatItNeeds) {
  const geometry::RigGeometry g = Rig();
  AutoBracket settings;
  settings.longest_max_s = 1;
  const MeteringResult m = ChooseBracket(MeteringShot(g, 0.1f, 5e-5f, 0.5f), 0.01, g, {}, settings);
  ASSERT_EQ(m.bracket_s.size(), 3u);
  EXPECT_NEAR(m.bracket_s.back(), 1.0, 1e-9);
  ASSERT_TRUE(m.sample_needs_s);
  EXPECT_NEAR(*m.sample_needs_s, 2.0, 1e-6);
  // A sample the metering shot cannot see at all reads as zero and needs the longest too.
  const MeteringResult black = ChooseBracket(MeteringShot(g, 0.1f, 0, 0.5f), 0.01, g, {}, settings);
  EXPECT_NEAR(black.bracket_s.back(), 1.0, 1e-9);
  EXPECT_TRUE(black.sample_needs_s);
}

}  // namespace
}  // namespace brdfrig::acquire
