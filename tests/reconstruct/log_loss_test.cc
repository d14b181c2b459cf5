// The validation score: values count both ways, a block below the noise floor (an upper bound)
// only where the model is brighter than it.
#include "reconstruct/log_loss.h"

#include <gtest/gtest.h>

#include <cmath>

#include "brdf/analytic.h"

namespace brdfrig::reconstruct {
namespace {

// One sample seen from 30° with the light at 20°, f the same in every channel.
DirectionSample At(double f, double weight = 1) {
  DirectionSample s;
  const double deg = M_PI / 180;
  s.l = brdf::Vec3(-std::sin(20 * deg), 0, std::cos(20 * deg));
  s.v = brdf::Vec3(std::sin(30 * deg), 0, std::cos(30 * deg));
  s.f = {f, f, f};
  s.weight = weight;
  return s;
}

constexpr Epsilon kEps = {1e-4, 1e-4, 1e-4};

// The residual of one channel, as the score defines it.
double Residual(double model, double data, const DirectionSample& s) {
  return std::log(kEps[0] + model * s.l.z()) - std::log(kEps[0] + data * s.l.z());
}

TEST(LogLossTest, ABoundTheModelStaysBelowAddsNothingButItsWeight) {
  const brdf::Lambert model(brdf::Rgb::Constant(0.3));
  const double f = 0.3 / M_PI;
  const DirectionSample value = At(2 * f);  // the model is half as bright as this sample
  const double alone = LogLossRms(model, {value}, kEps);
  EXPECT_NEAR(alone, std::abs(Residual(f, 2 * f, value)), 1e-12);
  // A bound at twice the model says "no brighter than that": the model agrees with it, so it
  // adds no error, only weight (the photo's pixels the model is right about).
  const DirectionSample bound = At(2 * f, 3 * value.weight);
  const double with_bound = LogLossRms(model, {value}, kEps, {bound});
  EXPECT_NEAR(with_bound, alone / 2, 1e-12);  // sqrt(r² · 1 / (1 + 3))
}

TEST(LogLossTest, ABoundTheModelExceedsCountsAsAValueWould) {
  const brdf::Lambert model(brdf::Rgb::Constant(0.3));
  const double f = 0.3 / M_PI;
  // The photo saw nothing above a tenth of what the model predicts.
  const DirectionSample dark = At(f / 10);
  const double as_bound = LogLossRms(model, {}, kEps, {dark});
  EXPECT_NEAR(as_bound, Residual(f, f / 10, dark), 1e-12);
  EXPECT_GT(as_bound, 2);  // ln 10, less what eps takes
  EXPECT_DOUBLE_EQ(as_bound, LogLossRms(model, {dark}, kEps));
}

TEST(LogLossTest, WithoutSamplesOrBoundsThereIsNoScore) {
  const brdf::Lambert model(brdf::Rgb::Constant(0.3));
  EXPECT_TRUE(std::isnan(LogLossRms(model, {}, kEps)));
  EXPECT_TRUE(std::isnan(LogLossRms(model, {}, kEps, {})));
}

}  // namespace
}  // namespace brdfrig::reconstruct
