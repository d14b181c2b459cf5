// The in-plane slices and the albedo curve: the curves are the models' own values, the
// measured samples land where their geometry puts them, and the plots draw every model.
#include "evaluate/brdf_plots.h"

#include <gtest/gtest.h>

#include <cmath>

#include "brdf/analytic.h"
#include "brdf/metrics.h"
#include "common/angles.h"
#include "common/error.h"

namespace brdfrig::evaluate {
namespace {

brdf::Vec3 Direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

TEST(BrdfPlotsTest, InPlaneViewAngleIsSignedPositiveOnTheMirrorSide) {
  const BrdfPlotOptions options;
  // Any azimuth of the plane of incidence: the material is isotropic.
  for (double phi : {0.0, 1.0, -2.5}) {
    const brdf::Vec3 l = Direction(Radians(30), phi);
    const brdf::Vec3 mirror = Direction(Radians(30), phi + M_PI);
    const brdf::Vec3 back = Direction(Radians(50), phi);
    EXPECT_NEAR(Degrees(InPlaneViewAngle({l, mirror, {}}, Radians(30), options)), 30, 1e-9);
    EXPECT_NEAR(Degrees(InPlaneViewAngle({l, back, {}}, Radians(30), options)), -50, 1e-9);
    // Out of the plane by 10° (> 3°), or another incidence angle (> 3° away): not in the slice.
    const brdf::Vec3 aside = Direction(Radians(30), phi + M_PI - Radians(20));
    EXPECT_TRUE(std::isnan(InPlaneViewAngle({l, aside, {}}, Radians(30), options)));
    EXPECT_TRUE(std::isnan(InPlaneViewAngle({l, mirror, {}}, Radians(45), options)));
  }
}

TEST(BrdfPlotsTest, CurvesAreTheModelsValuesAndSamplesLandOnTheirModel) {
  const brdf::Ggx truth({brdf::Rgb(0.3, 0.1, 0.05), brdf::Rgb(0.9, 0.6, 0.35), 0.2});
  const brdf::Lambert fit(brdf::Rgb(0.4, 0.2, 0.1));
  // Samples of the truth along the 30° plane of incidence (turned to azimuth 0.7).
  std::vector<MeasuredSample> samples;
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  for (double theta_o = -60; theta_o <= 60; theta_o += 5) {
    const double phi = 0.7;
    const brdf::Vec3 l = Direction(Radians(31), phi);
    const brdf::Vec3 v = Direction(Radians(std::abs(theta_o)), theta_o > 0 ? phi + M_PI : phi);
    samples.push_back({l, v, truth.Eval(l, v, n)});
  }
  BrdfPlotOptions options;
  options.slice_theta_in_deg = {30, 60};
  options.slices_where_measured = false;  // the slices asked for, not the samples' 31°
  options.albedo_step_deg = 15;
  const BrdfPlots plots =
      ComputeBrdfPlots({{"truth", "truth", &truth}, {"fit", "fit", &fit}}, samples, options);
  ASSERT_EQ(plots.slices.size(), 2u);
  const BrdfSlice& s30 = plots.slices[0];
  ASSERT_EQ(s30.f.size(), 2u);
  ASSERT_EQ(s30.theta_out_deg.size(), 179u);  // −89° … 89°
  // The truth's curve peaks at the mirror direction; the Lambert fit is flat at ρ/π.
  const auto peak = std::max_element(s30.f[0].begin(), s30.f[0].end()) - s30.f[0].begin();
  EXPECT_NEAR(s30.theta_out_deg[static_cast<std::size_t>(peak)], 30, 1.0);
  for (double v : s30.f[1]) EXPECT_NEAR(v, brdf::Rgb(0.4, 0.2, 0.1).mean() / M_PI, 1e-12);
  // Every sample (θi 31°, within 3°) is in the 30° slice, none in the 60° one; each lies where
  // the truth's curve is at its angle (1° away in θi, so within the lobe's change over 1°).
  EXPECT_EQ(s30.samples_near, static_cast<int>(samples.size()));
  EXPECT_EQ(plots.slices[1].samples_near, 0);
  for (std::size_t i = 0; i < s30.sample_f.size(); ++i) {
    const double theta_o = s30.sample_theta_out_deg[i];
    const std::size_t k = static_cast<std::size_t>(std::lround(theta_o + 89));
    EXPECT_NEAR(s30.theta_out_deg[k], theta_o, 1e-6);
    EXPECT_NEAR(std::log(s30.sample_f[i]), std::log(s30.f[0][k]), 0.35) << theta_o;
  }
  // The albedo curve is brdf::DirectionalAlbedo's, every 15° from 0° to 75°.
  ASSERT_EQ(plots.albedo_theta_in_deg.size(), 6u);
  EXPECT_NEAR(plots.albedo[0][2], brdf::DirectionalAlbedo(truth, Radians(30)).mean(), 1e-12);
}

TEST(BrdfPlotsTest, SlicesGoWhereThePhotosMeasuredThePlaneOfIncidence) {
  const brdf::Lambert truth(brdf::Rgb(0.5, 0.5, 0.5));
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  std::vector<MeasuredSample> samples;
  auto add = [&](double theta_in, double theta_o, double azimuth_off_plane, int count) {
    for (int i = 0; i < count; ++i) {
      const brdf::Vec3 l = Direction(Radians(theta_in + 0.001 * i), 0.3);
      const brdf::Vec3 v = Direction(Radians(theta_o), 0.3 + M_PI + Radians(azimuth_off_plane));
      samples.push_back({l, v, truth.Eval(l, v, n)});
    }
  };
  add(22.4, 15, 0, 40);   // a mirror-side photo in the plane of incidence
  add(72.4, 70, 0, 25);   // another, at grazing light
  add(40.2, 30, 0, 5);    // too few to get a slice of its own
  add(80.0, 60, 50, 90);  // many samples, but far out of the plane: no slice
  const BrdfPlotOptions options;
  EXPECT_EQ(SliceAngles(samples, options), (std::vector<double>{22, 45, 72}));  // 45: filled up
  // Without samples (or when asked), the default slices.
  EXPECT_EQ(SliceAngles({}, options), options.slice_theta_in_deg);
  BrdfPlotOptions fixed;
  fixed.slices_where_measured = false;
  EXPECT_EQ(SliceAngles(samples, fixed), fixed.slice_theta_in_deg);
}

TEST(BrdfPlotsTest, TheSlicePlotsDrawTheTruthTheFitAndTheSamples) {
  const brdf::Ggx truth({brdf::Rgb(0.3, 0.1, 0.05), brdf::Rgb(0.9, 0.6, 0.35), 0.2});
  const brdf::Lambert fit(brdf::Rgb(0.4, 0.2, 0.1));
  const brdf::Vec3 l = Direction(Radians(45), 0), v = Direction(Radians(45), M_PI);
  const std::vector<MeasuredSample> samples = {{l, v, truth.Eval(l, v, brdf::Vec3::UnitZ())}};
  const nlohmann::json json = BrdfPlotsJson(
      ComputeBrdfPlots({{"truth", "truth", &truth}, {"fit", "fit (microfacet)", &fit}}, samples));
  ASSERT_EQ(json.at("slices").size(), 5u);
  EXPECT_EQ(json["slices"][0]["f"]["truth"].size(), 179u);
  const ReportSection section = BrdfPlotsSection(json);
  ASSERT_EQ(section.svg_plots.size(), 6u);  // five slices, the albedo
  for (const std::string& svg : section.svg_plots) {
    EXPECT_NE(svg.find("data-label='truth'"), std::string::npos);
    EXPECT_NE(svg.find("data-label='fit (microfacet)'"), std::string::npos);
  }
  // The 45° slice holds the one sample, drawn as a dot; its axis is logarithmic.
  const std::string& s45 = section.svg_plots[2];
  EXPECT_NE(s45.find("data-label='measured (1)'"), std::string::npos);
  EXPECT_NE(s45.find("log scale"), std::string::npos);
  EXPECT_EQ(section.svg_plots[0].find("measured ("), std::string::npos);
}

TEST(BrdfPlotsTest, BadOptionsAndModelsAreRefused) {
  BrdfPlotOptions options;
  options.slice_theta_in_deg = {0};
  EXPECT_THROW(options.Validate(), OptionsError);
  const brdf::Lambert fit(brdf::Rgb(0.4, 0.2, 0.1));
  EXPECT_THROW(ComputeBrdfPlots({{"fit", "a", &fit}, {"fit", "b", &fit}}, {}), Error);
  EXPECT_THROW(ComputeBrdfPlots({{"fit", "a", nullptr}}, {}), Error);
}

}  // namespace
}  // namespace brdfrig::evaluate
