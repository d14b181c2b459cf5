// The light from the highlight, on a synthetic photo: a camera straight above the cut-out and a
// bright spot at the image centre, whose mirror direction is straight up.
#include "reconstruct/light_estimate.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "common/angles.h"
#include "common/error.h"
#include "geometry/camera.h"

namespace brdfrig::reconstruct {
namespace {

struct Photo {
  geometry::Intrinsics k{400, 300, 555, 555, 200, 150};
  geometry::CameraPose pose = geometry::LookAt({0, 0, 0.5}, {0, 0, 0}, {0, 1, 0});
  geometry::TargetGeometry target;
  cv::Mat radiance = cv::Mat(300, 400, CV_32FC3, cv::Scalar::all(0.1));
  cv::Mat valid = cv::Mat(300, 400, CV_8U, cv::Scalar(255));
  Photo() { cv::circle(radiance, {200, 150}, 4, cv::Scalar::all(5.0), cv::FILLED); }
  LightEstimate Estimate(const geometry::Vec3& nominal_light) const {
    return EstimateLight(radiance, valid, PlaneView(k, pose), target, nominal_light, {});
  }
};

TEST(LightEstimateTest, AHighlightNearTheNominalMirrorDirectionPlacesTheLight) {
  const Photo photo;
  // The nominal light 3° from the true mirror direction (a rig slightly off): the highlight
  // wins, at the nominal distance.
  const geometry::Vec3 nominal(0.6 * std::sin(Radians(3)), 0, 0.6 * std::cos(Radians(3)));
  const LightEstimate e = photo.Estimate(nominal);
  ASSERT_TRUE(e.from_highlight) << (e.warnings.empty() ? "" : e.warnings[0]);
  EXPECT_NEAR(e.position.x(), 0, 2e-3);
  EXPECT_NEAR(e.position.y(), 0, 2e-3);
  EXPECT_NEAR(e.position.z(), 0.6, 2e-3);
  EXPECT_NEAR(Degrees(e.nominal_disagreement_rad), 3, 0.3);
}

TEST(LightEstimateTest, ABrightSpotFarFromTheMirrorConfigurationIsNotTheHighlight) {
  const Photo photo;
  // The nominal light 60° away: the spot cannot be the mirror highlight of that light.
  const geometry::Vec3 nominal(0.6 * std::sin(Radians(60)), 0, 0.6 * std::cos(Radians(60)));
  const LightEstimate e = photo.Estimate(nominal);
  EXPECT_FALSE(e.from_highlight);
  EXPECT_EQ(e.position, nominal);
  ASSERT_EQ(e.warnings.size(), 1u);
  EXPECT_NE(e.warnings[0].find("60.0° from the rig's nominal light"), std::string::npos)
      << e.warnings[0];
  EXPECT_NE(e.warnings[0].find("not the mirror highlight"), std::string::npos) << e.warnings[0];
}

TEST(LightEstimateTest, OptionsAreValidated) {
  LightOptions options;
  options.max_nominal_disagreement_deg = 0;
  EXPECT_THROW(options.Validate(), OptionsError);
  options.max_nominal_disagreement_deg = 91;
  EXPECT_THROW(options.Validate(), OptionsError);
}

}  // namespace
}  // namespace brdfrig::reconstruct
