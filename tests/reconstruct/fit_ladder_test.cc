// The ladder: energy never created, one-sided data flagged, the seed_constrained rung's shared
// floor, validation positions never fitted, validation choosing a microfacet rung where the
// truth is one, and photos below the noise floor scored on their bounds.
#include "reconstruct/fit_ladder.h"

#include <gtest/gtest.h>

#include "brdf/metrics.h"
#include "reconstruct/energy.h"
#include "reconstruct/log_loss.h"
#include "tests/reconstruct/direction_patches.h"

namespace brdfrig::reconstruct {
namespace {

using testing::DesignedPatches;
using testing::Patch;
using testing::PatchDesign;

brdf::MicrofacetModelParams GgxTruth() {
  brdf::MicrofacetModelParams p;
  p.distribution = brdf::Distribution::kGgx;
  p.alpha = 0.1;
  p.f0 = brdf::Rgb(0.9, 0.6, 0.35);
  p.diffuse = brdf::Rgb(0.1, 0.05, 0.03);
  return p;
}

// Positions as the ladder sees them: direction samples of a patch, and the same pixels as
// slice samples (theta about the mirror direction; theta_in at the patch's centre).
std::vector<PositionSamples> Positions(const brdf::Brdf& truth,
                                       const std::vector<PatchDesign>& designs) {
  std::vector<PositionSamples> out;
  unsigned seed = 1;
  const int grid = 24;  // 576 samples a position: what block averaging gives, roughly
  for (const PatchDesign& d : designs) {
    PositionSamples p;
    p.index = static_cast<int>(out.size());
    p.directions = Patch(truth, d, grid, 0.01, seed++);
    const brdf::Vec3 n = brdf::Vec3::UnitZ();
    const DirectionSample& centre = p.directions.samples[(grid / 2) * grid + grid / 2];
    p.slices.theta_in = brdf::ComputeSliceAngles(centre.l, centre.v, n).theta_in;
    for (const DirectionSample& s : p.directions.samples) {
      p.slices.theta.push_back(brdf::ComputeSliceAngles(s.l, s.v, n).theta);
      p.slices.f.push_back(s.f);
      p.slices.weight.push_back(1);
      const HalfAngles a = HalfAnglesOf(s.l, s.v);
      p.directions.theta_h_max = std::max(p.directions.theta_h_max, a.theta_h);
    }
    p.slices.pixels_used = static_cast<int>(p.slices.theta.size());
    p.slices.angular_pixel_size = 0.1 / 0.5 / grid;
    out.push_back(std::move(p));
  }
  return out;
}

TEST(FitLadderTest, ValidationChoosesAMicrofacetRungOverTheSeedOnAGgxTruth) {
  const brdf::MicrofacetModel truth(GgxTruth());
  const LadderResult ladder = FitLadder(Positions(truth, DesignedPatches()), {}, {});
  std::cout << ladder.Summary();
  const RungResult& chosen = ladder.rungs[ladder.chosen];
  EXPECT_FALSE(brdf::IsSliceKind(chosen.kind)) << brdf::ModelKindName(chosen.kind);
  const RungResult& seed = ladder.rungs[0];
  ASSERT_EQ(seed.kind, brdf::ModelKind::kSeed);
  EXPECT_EQ(seed.fold_scores.size(), 6u);
  EXPECT_LT(chosen.score, 0.25 * seed.score);
  // Every rung but the seed (kept as the paper's model) conserves energy.
  for (const RungResult& r : ladder.rungs) {
    if (!r.fitted || r.kind == brdf::ModelKind::kSeed) continue;
    EXPECT_LE(MaxAlbedo(*r.material.Model()).albedo, 1.0 + 1e-3) << brdf::ModelKindName(r.kind);
  }
}

TEST(FitLadderTest, ValidationPositionsAreScoredButNeverFitted) {
  const brdf::MicrofacetModel truth(GgxTruth());
  std::vector<PositionSamples> all = Positions(truth, DesignedPatches());
  std::vector<PositionSamples> validation = {all.back()};
  validation[0].index = 99;
  all.pop_back();
  LadderOptions options;
  options.model = "ggx";
  const LadderResult ladder = FitLadder(all, validation, options);
  ASSERT_EQ(ladder.rungs.size(), 1u);
  ASSERT_EQ(ladder.rungs[0].validation_scores.size(), 1u);
  EXPECT_LT(ladder.rungs[0].validation_scores[0], 0.05);
  for (const auto& p : ladder.rungs[0].material.fit["positions"]) EXPECT_NE(p.get<int>(), 99);
}

TEST(FitLadderTest, EnergyIsNeverCreatedEvenWhenTheDataDo) {
  // Data from a model that reflects more than it receives (f0 = 1 and diffuse 0.9).
  brdf::MicrofacetModelParams p = GgxTruth();
  p.f0 = brdf::Rgb(1, 1, 1);
  p.diffuse = brdf::Rgb(0.9, 0.9, 0.9);
  p.alpha = 0.3;
  const brdf::MicrofacetModel truth(p);
  ASSERT_GT(MaxAlbedo(truth).albedo, 1.0);
  for (const char* kind : {"ggx", "microfacet", "seed_constrained"}) {
    LadderOptions options;
    options.model = kind;
    const LadderResult ladder = FitLadder(Positions(truth, DesignedPatches()), {}, options);
    const brdf::Material& m = ladder.rungs[0].material;
    EXPECT_LE(MaxAlbedo(*m.Model()).albedo, 1.0 + 1e-3) << kind;
  }
}

TEST(FitLadderTest, TheDefaultRungNeverCreatesEnergy) {
  // Data that reflect more than they receive: the seed's slices follow them (they are kept as
  // the paper wrote them), so validation alone might prefer them; the default must not.
  brdf::MicrofacetModelParams p = GgxTruth();
  p.f0 = brdf::Rgb(1, 1, 1);
  p.diffuse = brdf::Rgb(0.9, 0.9, 0.9);
  p.alpha = 0.3;
  const brdf::MicrofacetModel truth(p);
  const LadderResult ladder = FitLadder(Positions(truth, DesignedPatches()), {}, LadderOptions{});
  ASSERT_GE(ladder.chosen, 0);
  const RungResult& chosen = ladder.rungs[ladder.chosen];
  EXPECT_TRUE(chosen.ConservesEnergy()) << brdf::ModelKindName(chosen.kind);
  EXPECT_LE(MaxAlbedo(*chosen.material.Model()).albedo, 1.0 + 1e-3);
  for (const RungResult& r : ladder.rungs) {
    if (!r.fitted) continue;
    EXPECT_NEAR(r.max_albedo, MaxAlbedo(*r.material.Model()).albedo, 1e-9);
    EXPECT_EQ(ladder.Json()[&r - &ladder.rungs[0]]["max_albedo"].get<double>(), r.max_albedo);
  }
}

TEST(FitLadderTest, MirrorOnlyDataFlagTheDiffuseLevelUnobserved) {
  brdf::MicrofacetModelParams p = GgxTruth();
  p.alpha = 0.05;
  const brdf::MicrofacetModel truth(p);
  LadderOptions options;
  options.model = "ggx";
  const LadderResult ladder =
      FitLadder(Positions(truth, {{15, 15}, {30, 30}, {45, 45}}), {}, options);
  const nlohmann::json& fit = ladder.rungs[0].material.fit;
  std::cout << fit.dump() << "\n";
  for (const auto& observed : fit["diffuse_observed"]) EXPECT_FALSE(observed.get<bool>());
  EXPECT_LT(fit["max_theta_h_deg"].get<double>(), 10);
}

TEST(FitLadderTest, SeedConstrainedSharesOneMeasuredDiffuseLevel) {
  brdf::MicrofacetModelParams p = GgxTruth();
  p.f0 = brdf::Rgb(0.05, 0.05, 0.05);
  p.diffuse = brdf::Rgb(0.3, 0.2, 0.1);
  const brdf::MicrofacetModel truth(p);
  LadderOptions options;
  options.model = "seed_constrained";
  const LadderResult ladder = FitLadder(Positions(truth, DesignedPatches()), {}, options);
  const brdf::Material& m = ladder.rungs[0].material;
  // Six positions at five incidence angles (two share the light at 15°: pooled).
  ASSERT_EQ(m.slices.size(), 5u);
  for (int c = 0; c < 3; ++c) {
    for (const brdf::Slice& s : m.slices) {
      EXPECT_DOUBLE_EQ(s.channel[c].a2, m.slices[0].channel[c].a2);
    }
    // Far from the lobe the data are the diffuse level (plus a little of GGX's tail).
    const double want = p.diffuse[c] / M_PI;
    EXPECT_NEAR(m.slices[0].channel[c].a2, want, 0.15 * want) << c;
  }
}

}  // namespace
}  // namespace brdfrig::reconstruct

namespace brdfrig::reconstruct {
namespace {

// A photo's pixel count follows the camera, not the BRDF: giving one position's samples ten
// times the pixels (a closer camera) must not change the fit.
TEST(FitLadderTest, APositionsPixelCountDoesNotChangeItsWeightInTheFit) {
  brdf::MicrofacetModelParams p = GgxTruth();
  p.alpha = 0.2;
  const brdf::MicrofacetModel truth(p);
  std::vector<PositionSamples> positions = Positions(truth, DesignedPatches());
  std::vector<PositionSamples> closer = positions;
  for (DirectionSample& s : closer[2].directions.samples) s.weight *= 10;
  LadderOptions options;
  options.model = "ggx";
  const brdf::MicrofacetModelParams a =
      FitLadder(positions, {}, options).rungs[0].material.microfacet;
  const brdf::MicrofacetModelParams b = FitLadder(closer, {}, options).rungs[0].material.microfacet;
  EXPECT_NEAR(a.alpha, b.alpha, 1e-6 * a.alpha);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(a.f0[c], b.f0[c], 1e-6 * a.f0[c]);
    EXPECT_NEAR(a.diffuse[c], b.diffuse[c], 1e-6 * a.diffuse[c] + 1e-12);
  }
}

// Leave one position out refits every rung, the slice rungs too: what the held-out photo shows
// cannot reach its own prediction (the slices share pooled angles, a diffuse floor and an
// energy scale). Each fold's score is the score of the rung refitted on the other positions.
TEST(FitLadderTest, EveryFoldIsARefitWithoutItsHeldOutPosition) {
  const brdf::MicrofacetModel truth(GgxTruth());
  std::vector<PositionSamples> positions = Positions(truth, DesignedPatches());
  // A held-out photo that disagrees with the rest: had it leaked into its fold, the fold would
  // predict it better than a refit without it does.
  for (DirectionSample& s : positions[1].directions.samples) {
    for (double& f : s.f) f *= 3;
  }
  for (auto& f : positions[1].slices.f) {
    for (double& x : f) x *= 3;
  }
  const LadderResult ladder = FitLadder(positions, {}, {});
  std::vector<const PositionSamples*> rest;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (i != 1) rest.push_back(&positions[i]);
  }
  const auto& held = positions[1].directions.samples;
  const Epsilon eps = LossEpsilon(held, MicrofacetFitOptions{}.epsilon_fraction);
  for (brdf::ModelKind kind : {brdf::ModelKind::kSeed, brdf::ModelKind::kSeedConstrained}) {
    const RungResult& rung = ladder.rungs[static_cast<int>(kind == brdf::ModelKind::kSeed ? 0 : 1)];
    ASSERT_EQ(rung.kind, kind);
    ASSERT_EQ(rung.fold_positions[1], 1);
    const brdf::Material refit = FitRung(kind, rest, {}, false);
    EXPECT_DOUBLE_EQ(rung.fold_scores[1], LogLossRms(*refit.Model(), held, eps))
        << brdf::ModelKindName(kind);
  }
}

// The folds take their slice fits from a memo: what it returns must be what a fresh fit
// returns, the first time and from the memo, and a slice held to a diffuse level (or fitted
// with a covariance) must not be served the free fit of the same positions.
TEST(FitLadderTest, TheSliceMemoReturnsAFreshFitForEachDiffuseLevelAndCovariance) {
  const brdf::MicrofacetModel truth(GgxTruth());
  const std::vector<PositionSamples> positions = Positions(truth, DesignedPatches());
  const BrdfSamples& samples = positions[0].slices;
  SliceFitOptions plain;
  plain.covariance = false;
  const SliceFitOptions with_covariance;
  const std::array<double, 3> level = {0.01, 0.02, 0.03};
  const auto expect_same = [](const SliceFit& a, const SliceFit& b, const char* what) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(a.slice.channel[c].a1, b.slice.channel[c].a1) << what;
      EXPECT_EQ(a.slice.channel[c].a2, b.slice.channel[c].a2) << what;
      EXPECT_EQ(a.slice.channel[c].h, b.slice.channel[c].h) << what;
      EXPECT_EQ(a.slice.channel[c].x0, b.slice.channel[c].x0) << what;
      EXPECT_EQ(std::isnan(a.channel[c].stddev[0]), std::isnan(b.channel[c].stddev[0])) << what;
    }
  };
  SliceFitMemo memo;
  for (int pass = 0; pass < 2; ++pass) {  // the second pass is served from the memo
    expect_same(memo.Fit({0}, samples, plain, std::nullopt), FitSlice(samples, plain), "free");
    expect_same(memo.Fit({0}, samples, plain, level), FitSlice(samples, plain, level), "held");
    expect_same(memo.Fit({0}, samples, with_covariance, std::nullopt),
                FitSlice(samples, with_covariance), "covariance");
  }
  EXPECT_NE(memo.Fit({0}, samples, plain, level).slice.channel[2].a2,
            memo.Fit({0}, samples, plain, std::nullopt).slice.channel[2].a2);
  EXPECT_TRUE(std::isnan(memo.Fit({0}, samples, plain, std::nullopt).channel[0].stddev[0]));
  EXPECT_FALSE(
      std::isnan(memo.Fit({0}, samples, with_covariance, std::nullopt).channel[0].stddev[0]));
}

// A photo whose every block was darker than the sensor's noise floor has no direction sample.
// It cannot be held out (there is nothing to score on), so the folds are the other positions,
// every score finite, and the choice is made as usual.
TEST(FitLadderTest, APositionWithNoDirectionSampleIsNotAFold) {
  const brdf::MicrofacetModel truth(GgxTruth());
  std::vector<PositionSamples> positions = Positions(truth, DesignedPatches());
  positions[4].directions.samples.clear();
  const LadderResult ladder = FitLadder(positions, {}, {});
  ASSERT_GE(ladder.chosen, 0);
  for (const RungResult& rung : ladder.rungs) {
    if (!rung.fitted) continue;
    EXPECT_EQ(rung.fold_positions, (std::vector<int>{0, 1, 2, 3, 5}))
        << brdf::ModelKindName(rung.kind);
    EXPECT_TRUE(std::isfinite(rung.score)) << brdf::ModelKindName(rung.kind);
  }
  EXPECT_NE(ladder.rungs[ladder.chosen].kind, brdf::ModelKind::kSeed);
}

// A photo wholly below the noise floor still says where the material is dark: it is held out
// like the others and each rung is scored on its bounds, a rung brighter than a bound
// contradicted by it.
TEST(FitLadderTest, APhotoWhollyBelowTheNoiseFloorIsAFoldScoredOnItsBounds) {
  const brdf::MicrofacetModel truth(GgxTruth());
  std::vector<PositionSamples> positions = Positions(truth, DesignedPatches());
  // The photo saw at most a tenth of what the material reflects there.
  DirectionSamples& dark = positions[4].directions;
  dark.bounds = dark.samples;
  for (DirectionSample& s : dark.bounds) {
    for (double& f : s.f) f /= 10;
  }
  dark.samples.clear();
  const LadderResult ladder = FitLadder(positions, {}, {});
  ASSERT_GE(ladder.chosen, 0);
  std::vector<const PositionSamples*> rest;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (i != 4) rest.push_back(&positions[i]);
  }
  const Epsilon eps = LossEpsilon(dark.bounds, MicrofacetFitOptions{}.epsilon_fraction);
  const RungResult& seed = ladder.rungs[0];
  ASSERT_EQ(seed.kind, brdf::ModelKind::kSeed);
  ASSERT_EQ(seed.fold_positions, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  const brdf::Material refit = FitRung(brdf::ModelKind::kSeed, rest, {}, false);
  EXPECT_DOUBLE_EQ(seed.fold_scores[4], LogLossRms(*refit.Model(), {}, eps, dark.bounds));
  for (const RungResult& rung : ladder.rungs) {
    if (!rung.fitted) continue;
    // Every rung fitted to the other photos is brighter than these bounds: about ln 10 off.
    EXPECT_GT(rung.fold_scores[4], 1) << brdf::ModelKindName(rung.kind);
    EXPECT_TRUE(std::isfinite(rung.score)) << brdf::ModelKindName(rung.kind);
  }
}

// A fold must keep a photo with values to fit: with one such photo there are no folds (the
// choice falls back on the fits' own residuals), however many photos hold only bounds.
TEST(FitLadderTest, FoldsNeedTwoPhotosWithValues) {
  const brdf::MicrofacetModel truth(GgxTruth());
  std::vector<PositionSamples> positions = Positions(truth, DesignedPatches());
  for (std::size_t i = 1; i < positions.size(); ++i) {
    DirectionSamples& d = positions[i].directions;
    d.bounds = d.samples;
    d.samples.clear();
  }
  const LadderResult ladder = FitLadder(positions, {}, {});
  ASSERT_GE(ladder.chosen, 0);
  for (const RungResult& rung : ladder.rungs) {
    EXPECT_TRUE(rung.fold_positions.empty()) << brdf::ModelKindName(rung.kind);
  }
}

}  // namespace
}  // namespace brdfrig::reconstruct
