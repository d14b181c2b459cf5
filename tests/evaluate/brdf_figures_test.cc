#include "evaluate/brdf_figures.h"

#include <gtest/gtest.h>

#include "brdf/analytic.h"
#include "common/error.h"

namespace brdfrig::evaluate {
namespace {

TEST(BrdfFiguresTest, TheTruthAgainstItselfHasNoError) {
  const brdf::Ggx ggx({brdf::Rgb(0.3, 0.1, 0.05), brdf::Rgb(0.9, 0.6, 0.35), 0.2});
  const BrdfFigures f = CompareBrdf(ggx, ggx);
  ASSERT_EQ(f.albedo.size(), 7u);
  EXPECT_EQ(f.albedo.back().theta_in_deg, 80);
  EXPECT_NEAR(f.log_cosine_error, 0, 1e-12);
  EXPECT_NEAR(f.max_albedo_error, 0, 1e-12);
  EXPECT_NE(f.Report().find("log-cosine"), std::string::npos);
}

TEST(BrdfFiguresTest, AlbedoErrorIsTheWorstChannelsRelativeError) {
  // Lambert's directional albedo is its rho at every angle (up to quadrature).
  const brdf::Lambert truth(brdf::Rgb(0.5, 0.5, 0.1));
  const brdf::Lambert fitted(brdf::Rgb(0.5, 0.55, 0.2));  // +10 % green, +100 % blue
  const BrdfFigures f = CompareBrdf(truth, fitted, {{0, 45}});
  ASSERT_EQ(f.albedo.size(), 2u);
  for (const AlbedoAtAngle& a : f.albedo) EXPECT_NEAR(a.relative_error, 1.0, 1e-6);
  EXPECT_NEAR(f.max_albedo_error, 1.0, 1e-6);
  EXPECT_GT(f.log_cosine_error, 0);
}

TEST(BrdfFiguresTest, AnglesMustBeAboveTheSurface) {
  EXPECT_THROW(BrdfFiguresOptions({{0, 90}}).Validate(), OptionsError);
}

}  // namespace
}  // namespace brdfrig::evaluate
