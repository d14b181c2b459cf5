#include "prior/measured_prior.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

#include "brdf/nbrdf_library.h"
#include "common/error.h"
#include "prior/build_prior.h"
#include "prior/prior_fit.h"

namespace brdfrig::prior {
namespace {

using ::testing::HasSubstr;

// A coarse grid keeps the test fast; the shipped prior's grid is the default.
PriorBuildOptions SmallOptions() {
  PriorBuildOptions o;
  o.grid.theta_h = 24;
  o.grid.theta_d = 12;
  o.grid.phi_d = 4;
  o.max_components = 40;
  o.noise_sigma = 0.1;
  return o;
}

const TrainingSet& Set() {
  static const TrainingSet set = ReadTrainingSet({brdf::NbrdfDirectory()}, SmallOptions());
  return set;
}

double TableRms(const brdf::TableValues& a, const brdf::TableValues& b) {
  double sum = 0;
  long n = 0;
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < a[c].size(); ++i, ++n) sum += std::pow(a[c][i] - b[c][i], 2);
  }
  return std::sqrt(sum / n);
}

// Observations of a table at every node (dense data) or only within `max_theta_h` (beyond
// `min_theta_h`, and within `max_theta_d`, when given).
std::vector<Observation> Observe(const brdf::TableValues& truth, const brdf::RusinkiewiczGrid& g,
                                 double max_theta_h, double min_theta_h = -1,
                                 double max_theta_d = M_PI) {
  std::vector<Observation> out;
  const brdf::RusinkiewiczTable table(g, truth);
  for (int ih = 0; ih < g.theta_h; ++ih) {
    for (int id = 0; id < g.theta_d; ++id) {
      for (int ip = 0; ip < g.phi_d; ++ip) {
        const brdf::HalfDiffAngles a = brdf::NodeAngles(g, ih, id, ip);
        if (a.theta_h > max_theta_h || a.theta_h <= min_theta_h || a.theta_d > max_theta_d) {
          continue;
        }
        Observation o;
        brdf::FromHalfDiffAngles(a, &o.l, &o.v);
        if (o.l.z() <= 0.01 || o.v.z() <= 0.01) continue;
        o.f = table.EvalLocal(o.l, o.v);
        out.push_back(o);
      }
    }
  }
  return out;
}

TEST(MeasuredPrior, EveryShippedMaterialIsTabulatedWithItsLicenceAndHash) {
  ASSERT_EQ(Set().materials.size(), 80u);
  for (const TrainingMaterial& m : Set().materials) {
    EXPECT_EQ(m.sha256.size(), 64u) << m.name;
    EXPECT_THAT(m.licence, HasSubstr("MIT")) << m.name;
    EXPECT_THAT(m.database, ::testing::AnyOf("merl", "rgl", "dtu")) << m.name;
  }
}

TEST(MeasuredPrior, LeftOutMaterialIsReconstructedFromPartialDataBetterThanTheMean) {
  const PriorBuildOptions options = SmallOptions();
  double fit_error = 0, mean_error = 0;
  const std::vector<int> held_out = {3, 17, 42, 66};
  for (const int m : held_out) {
    const MeasuredPrior p = BuildPrior(Set(), options, m);
    ASSERT_EQ(p.training.size(), 79u);
    const brdf::TableValues& truth = Set().tables[m];
    // Photos that saw θh up to 30°: the rest comes from the prior.
    PriorFitOptions fit_options;
    fit_options.correct = false;
    const PriorFitResult fit = FitPrior(p, Observe(truth, p.grid, 0.5), fit_options);
    brdf::TableValues mean;
    for (auto& c : mean) c.assign(p.mean.data(), p.mean.data() + p.mean.size());
    fit_error += TableRms(fit.table, truth) / held_out.size();
    mean_error += TableRms(mean, truth) / held_out.size();
  }
  EXPECT_LT(fit_error, 0.6 * mean_error) << fit_error << " vs the mean's " << mean_error;
}

// The prior local to the training channels the data resemble (PriorFitOptions::bandwidth)
// against one Gaussian over all of them: on materials left out of the prior, seen up to θh 30°,
// the local prior's table lies closer to the truth on average.
TEST(MeasuredPrior, LocalPriorFillsUnseenDirectionsBetterThanOneGaussian) {
  PriorBuildOptions options = SmallOptions();
  options.noise_sigma = 1;
  double local_error = 0, global_error = 0;
  for (int m = 5; m < 80; m += 10) {
    const MeasuredPrior p = BuildPrior(Set(), options, m);
    const std::vector<Observation> seen = Observe(Set().tables[m], p.grid, 0.5);
    PriorFitOptions local, global;
    local.correct = global.correct = false;
    global.bandwidth = 0;
    local_error += TableRms(FitPrior(p, seen, local).table, Set().tables[m]) / 8;
    global_error += TableRms(FitPrior(p, seen, global).table, Set().tables[m]) / 8;
  }
  EXPECT_LT(local_error, 0.9 * global_error) << local_error << " vs " << global_error;
}

// The local prior's weights are the evidence of each training channel: a training material
// seen over the whole hemisphere is recognised: its own three channels (a grey material's
// channels are alike) carry most of each channel's weight, which sums to one.
TEST(MeasuredPrior, LocalPriorLeansOnTheTrainingMaterialTheDataCameFrom) {
  PriorBuildOptions options = SmallOptions();
  options.noise_sigma = 1;
  const MeasuredPrior p = BuildPrior(Set(), options);
  for (const int m : {7, 33, 61}) {
    const PriorFitResult fit = FitPrior(p, Observe(Set().tables[m], p.grid, M_PI / 2), {});
    for (int ch = 0; ch < 3; ++ch) {
      const Eigen::VectorXd& w = fit.neighbour_weights[ch];
      ASSERT_EQ(w.size(), 3 * 80);
      EXPECT_NEAR(w.sum(), 1, 1e-9);
      EXPECT_GT(w.segment(3 * m, 3).sum(), 0.5) << Set().materials[m].name << " channel " << ch;
    }
  }
  PriorFitOptions global;
  global.bandwidth = 0;
  EXPECT_EQ(FitPrior(p, Observe(Set().tables[7], p.grid, 0.5), global).neighbour_weights[0].size(),
            0);
}

// Step 2 of the fit: where samples are, the table follows them more closely than the prior's
// components alone can.
TEST(MeasuredPrior, CorrectionMovesTheTableTowardsTheSamplesWhereTheyAre) {
  PriorBuildOptions options = SmallOptions();
  options.noise_sigma = 1;  // a strong prior: the components leave visible residuals
  const MeasuredPrior p = BuildPrior(Set(), options, 42);
  const brdf::TableValues& truth = Set().tables[42];
  const std::vector<Observation> seen = Observe(truth, p.grid, 0.3);
  PriorFitOptions plain;
  plain.correct = false;
  const PriorFitResult without = FitPrior(p, seen, plain);
  const PriorFitResult with = FitPrior(p, seen, {});
  const auto error_at_samples = [&](const brdf::TableValues& table) {
    const brdf::RusinkiewiczTable t(p.grid, table);
    double sum = 0;
    for (const Observation& o : seen) {
      const brdf::Rgb f = t.EvalLocal(o.l, o.v);
      const double c = brdf::CosineProduct(p.grid, o.l, o.v);
      for (int ch = 0; ch < 3; ++ch) {
        sum += std::pow(brdf::MapValue(p.grid, f[ch], c) - brdf::MapValue(p.grid, o.f[ch], c), 2);
      }
    }
    return std::sqrt(sum / (3.0 * seen.size()));
  };
  EXPECT_LT(error_at_samples(with.table), 0.5 * error_at_samples(without.table))
      << error_at_samples(with.table) << " vs " << error_at_samples(without.table);
}

// A photo's patch says something about its neighbourhood too: a material's departure from
// what the components can represent is smooth, so the correction spread over neighbouring
// nodes (correction_reach) brings the nodes beside the patch closer to the truth, and leaves
// the nodes far from it as the components put them.
TEST(MeasuredPrior, CorrectionReachImprovesTheNodesBesideThePatchOnly) {
  PriorBuildOptions options = SmallOptions();
  options.noise_sigma = 1;
  const MeasuredPrior p = BuildPrior(Set(), options, 42);
  const brdf::TableValues& truth = Set().tables[42];
  const std::vector<Observation> seen = Observe(truth, p.grid, 0.3);
  PriorFitOptions own, reach;
  own.correction_reach = 0;
  reach.correction_reach = 1;
  const PriorFitResult a = FitPrior(p, seen, own), b = FitPrior(p, seen, reach);
  double beside_own = 0, beside_reach = 0, far_change = 0;
  for (int ih = 0; ih < p.grid.theta_h; ++ih) {
    const double theta_h = brdf::NodeAngles(p.grid, ih, 0, 0).theta_h;
    for (int id = 0; id < p.grid.theta_d; ++id) {
      for (int ip = 0; ip < p.grid.phi_d; ++ip) {
        const int n = p.grid.Index(ih, id, ip);
        for (int c = 0; c < 3; ++c) {
          if (theta_h > 0.3 && theta_h < 0.5) {
            beside_own += std::pow(a.table[c][n] - truth[c][n], 2);
            beside_reach += std::pow(b.table[c][n] - truth[c][n], 2);
          } else if (theta_h > 0.9) {
            far_change = std::max(far_change, std::abs(a.table[c][n] - b.table[c][n]));
          }
        }
      }
    }
  }
  EXPECT_LT(beside_reach, 0.9 * beside_own) << beside_reach << " vs " << beside_own;
  EXPECT_EQ(far_change, 0);
}

// A black mirror photographed away from its highlight is darker than the photos' noise floor:
// those directions give bounds, not values. Without them the prior fills the directions with
// what brighter training materials do; with them the fit stays below every bound it can.
TEST(MeasuredPrior, UpperBoundsKeepADarkMaterialDarkWherePhotosSawOnlyNoise) {
  PriorBuildOptions options = SmallOptions();
  options.noise_sigma = 1;
  const auto& materials = Set().materials;
  const auto it = std::find_if(materials.begin(), materials.end(), [](const TrainingMaterial& m) {
    return m.name == "black-obsidian";
  });
  ASSERT_NE(it, materials.end());
  const int index = static_cast<int>(it - materials.begin());
  const MeasuredPrior p = BuildPrior(Set(), options, index);
  const brdf::TableValues& truth = Set().tables[index];
  std::vector<Observation> seen = Observe(truth, p.grid, 0.1, -1, 0.4);
  std::vector<Observation> bounds = Observe(truth, p.grid, M_PI / 2, 0.3);
  for (Observation& o : bounds) {
    o.f *= 1.2;  // a floor just above the truth
    o.upper_bound = true;
  }
  const PriorFitResult without = FitPrior(p, seen, {});
  std::vector<Observation> both = seen;
  both.insert(both.end(), bounds.begin(), bounds.end());
  const PriorFitResult with = FitPrior(p, both, {});
  EXPECT_EQ(with.observations, without.observations);
  EXPECT_EQ(with.bounds, static_cast<int>(bounds.size()));
  EXPECT_GT(with.bounds_active, 0);
  // How far, in q, a fit's table rises above the bounds, as an RMS over all of them.
  const auto excess = [&](const PriorFitResult& fit) {
    const brdf::RusinkiewiczTable t(p.grid, fit.table);
    double sum = 0;
    for (const Observation& o : bounds) {
      const brdf::Rgb f = t.EvalLocal(o.l, o.v);
      const double c = brdf::CosineProduct(p.grid, o.l, o.v);
      for (int ch = 0; ch < 3; ++ch) {
        sum += std::pow(
            std::max(0.0, brdf::MapValue(p.grid, f[ch], c) - brdf::MapValue(p.grid, o.f[ch], c)),
            2);
      }
    }
    return std::sqrt(sum / (3.0 * bounds.size()));
  };
  EXPECT_GT(excess(without), 0.5) << "the test's bounds do not bind: " << excess(without);
  EXPECT_LT(excess(with), 0.3 * excess(without)) << excess(with) << " vs " << excess(without);
  EXPECT_LT(TableRms(with.table, truth), 0.7 * TableRms(without.table, truth))
      << TableRms(with.table, truth) << " vs " << TableRms(without.table, truth);
}

TEST(MeasuredPrior, TrainingMaterialFromDenseDataIsAlmostExact) {
  const MeasuredPrior p = BuildPrior(Set(), SmallOptions());
  const brdf::TableValues& truth = Set().tables[10];
  const PriorFitResult fit = FitPrior(p, Observe(truth, p.grid, M_PI / 2), {});
  EXPECT_LT(TableRms(fit.table, truth), 0.05);
  EXPECT_FALSE(fit.outside_prior) << fit.misfit;
}

// A "material" no gonioreflectometer measured (values scattered over four decades with no
// structure) leaves residuals the components cannot explain; a left-out real one does not.
TEST(MeasuredPrior, AMaterialUnlikeTheTrainingSetIsFlaggedOutsideThePrior) {
  PriorBuildOptions options = SmallOptions();
  options.noise_sigma = 1;
  const MeasuredPrior p = BuildPrior(Set(), options, 20);
  std::vector<Observation> real = Observe(Set().tables[20], p.grid, 0.6);
  EXPECT_FALSE(FitPrior(p, real, {}).outside_prior) << FitPrior(p, real, {}).misfit;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> decades(-2, 2);
  for (Observation& o : real) o.f = brdf::Rgb::Constant(std::pow(10.0, decades(rng)));
  const PriorFitResult odd = FitPrior(p, real, {});
  EXPECT_TRUE(odd.outside_prior) << odd.misfit;
}

TEST(MeasuredPrior, FileRoundTripsAndBrokenFilesNameTheProblem) {
  PriorBuildOptions options = SmallOptions();
  options.max_components = 8;
  const MeasuredPrior p = BuildPrior(Set(), options);
  const std::string path = testing::TempDir() + "/p.prior";
  WritePrior(p, path);
  const MeasuredPrior back = ReadPrior(path);
  EXPECT_EQ(back.training.size(), p.training.size());
  EXPECT_EQ(back.training[5].sha256, p.training[5].sha256);
  EXPECT_EQ(back.grid, p.grid);
  EXPECT_NEAR((back.components - p.components).cwiseAbs().maxCoeff(), 0, 1e-6);
  EXPECT_NEAR(back.noise_sigma, p.noise_sigma, 1e-12);

  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto expect_error = [&](const std::string& text, const std::string& what) {
    const std::string broken = testing::TempDir() + "/broken.prior";
    std::ofstream(broken, std::ios::binary) << text;
    try {
      ReadPrior(broken);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const FileError& e) {
      EXPECT_THAT(e.what(), HasSubstr("broken.prior"));
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
  };
  expect_error("hello", "not a brdfrig prior");
  expect_error(bytes.substr(0, bytes.size() - 10), "cut short");
  std::string nan = bytes;
  const float bad = std::nanf("");
  std::memcpy(nan.data() + nan.size() - 4, &bad, 4);
  expect_error(nan, "not finite");
  std::string version = bytes;
  version.replace(version.find("\"version\": 1"), 12, "\"version\": 7");
  expect_error(version, "version");
}

}  // namespace
}  // namespace brdfrig::prior
