// Coverage in (θh, θd) from the nominal geometry, and the plan designer on the default rig.
#include "coverage/coverage.h"

#include <gtest/gtest.h>

#include <chrono>

#include "common/error.h"
#include "coverage/design_request.h"
#include "coverage/designer.h"
#include "coverage/prior_objective.h"

namespace brdfrig::coverage {
namespace {

constexpr double kDegree = M_PI / 180;

geometry::RigGeometry DefaultRig() {
  return geometry::ParseRigGeometry(
      LoadYamlFile(BRDFRIG_SOURCE_DIR "/sim/scenes/ggx.yaml").Required("rig"));
}

std::vector<geometry::AxisPositions> MirrorPlan() {
  std::vector<geometry::AxisPositions> plan;
  for (int theta = 15; theta <= 65; theta += 10) {
    plan.push_back({{"camera_arm", theta * kDegree}, {"light_arm", -theta * kDegree}});
  }
  return plan;
}

TEST(CoverageTest, HalfDiffAnglesOfKnownConfigurations) {
  // Mirror configuration at 30°: the half vector is the normal, θd the incidence angle.
  const geometry::Vec3 l(0, std::sin(30 * kDegree), std::cos(30 * kDegree));
  const geometry::Vec3 v(0, -std::sin(30 * kDegree), std::cos(30 * kDegree));
  HalfDiff hd = ToHalfDiff(l, v);
  EXPECT_NEAR(hd.theta_h, 0, 1e-9);
  EXPECT_NEAR(hd.theta_d, 30 * kDegree, 1e-9);
  // Retro-reflection: l = v, θd = 0 and θh = the angle from the normal.
  hd = ToHalfDiff(l, l);
  EXPECT_NEAR(hd.theta_h, 30 * kDegree, 1e-9);
  EXPECT_NEAR(hd.theta_d, 0, 1e-7);
}

TEST(CoverageTest, BinsAreSqrtWarpedInThetaH) {
  EXPECT_EQ(ThetaHBin(0, 32), 0);
  EXPECT_EQ(ThetaHBin(M_PI / 2, 32), 31);
  // A quarter of the way along the axis is θh = π/2 / 16.
  EXPECT_EQ(ThetaHBin(M_PI / 2 / 16 * 1.0001, 32), 8);
  EXPECT_NEAR(ThetaHEdge(8, 32), M_PI / 2 / 16, 1e-12);
  EXPECT_EQ(ThetaDBin(M_PI / 4, 32), 16);
}

TEST(CoverageTest, MirrorPlanSeesOnlyTheFirstDegreesOfThetaH) {
  const CoverageMap map = ComputeCoverage(DefaultRig(), MirrorPlan(), {});
  ASSERT_EQ(map.positions.size(), 6u);
  for (std::size_t i = 0; i < map.positions.size(); ++i) {
    const PositionCoverage& c = map.positions[i];
    ASSERT_TRUE(c.observed) << c.problem;
    EXPECT_NEAR(c.theta_h_min, 0, 0.2 * kDegree);
    EXPECT_LT(c.theta_h_max, 13 * kDegree) << i;
    // θd around the incidence angle, spread about ±w/2d.
    EXPECT_NEAR(0.5 * (c.theta_d_min + c.theta_d_max), (15 + 10 * i) * kDegree, 2 * kDegree);
    EXPECT_NEAR(c.theta_in, (15 + 10 * i) * kDegree, 1e-9);
  }
  EXPECT_GT(map.covered_fraction, 0.02);
  EXPECT_LT(map.covered_fraction, 0.2);
  EXPECT_NE(map.ToString().find("covered fraction"), std::string::npos);
  const std::string svg = CoverageSvg(map, "mirror plan");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("camera_arm=35.0"), std::string::npos);
}

TEST(CoverageTest, ValidationPositionsDoNotCountAsFitted) {
  const auto plan = MirrorPlan();
  const CoverageMap map =
      ComputeCoverage(DefaultRig(), plan, {false, false, false, false, false, true});
  const CoverageMap five = ComputeCoverage(
      DefaultRig(), std::vector<geometry::AxisPositions>(plan.begin(), plan.begin() + 5), {});
  EXPECT_DOUBLE_EQ(map.covered_fraction, five.covered_fraction);
  EXPECT_GT(map.covered_fraction_with_validation, map.covered_fraction);
}

TEST(CoverageTest, SharedCellsCountWhatAnotherFittedPositionAlsoSees) {
  const auto plan = MirrorPlan();
  // The same position twice: each sees only cells the other sees too.
  const std::vector<geometry::AxisPositions> twice = {plan[0], plan[0]};
  const CoverageMap same = ComputeCoverage(DefaultRig(), twice, {});
  ASSERT_GT(same.positions[0].cells.size(), 0u);
  EXPECT_EQ(same.positions[0].shared_cells, static_cast<int>(same.positions[0].cells.size()));
  EXPECT_DOUBLE_EQ(same.shared_cell_fraction, 1);
  EXPECT_DOUBLE_EQ(same.shared_theta_h_fraction, 1);
  // Mirror photos 30° apart in θd share no cell, but their θh ranges (from 0) overlap.
  const std::vector<geometry::AxisPositions> apart = {plan[0], plan[3]};
  const CoverageMap distinct = ComputeCoverage(DefaultRig(), apart, {});
  EXPECT_EQ(distinct.positions[0].shared_cells, 0);
  EXPECT_DOUBLE_EQ(distinct.shared_cell_fraction, 0);
  EXPECT_GT(distinct.shared_theta_h_fraction, 0.5);
  // A validation position is not another fitted one: alone with it, a fitted one shares nothing.
  const CoverageMap with_validation = ComputeCoverage(DefaultRig(), twice, {false, true});
  EXPECT_EQ(with_validation.positions[0].shared_cells, 0);
  EXPECT_EQ(with_validation.positions[1].shared_cells,
            static_cast<int>(with_validation.positions[1].cells.size()));
}

TEST(DesignerTest, DefaultRigDesignBeatsTheMirrorPlanWithinConstraints) {
  const geometry::RigGeometry rig = DefaultRig();
  DesignOptions options;
  options.objective = "coverage";
  const auto start = std::chrono::steady_clock::now();
  const PlanDesign design = DesignPlan(rig, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s(%.2f s)\n", design.ToString().c_str(), seconds);
  ASSERT_EQ(design.positions.size(), 6u);
  EXPECT_TRUE(design.has_retro);
  EXPECT_TRUE(design.has_grazing);
  int off_specular = 0, mirror = 0;
  for (const DesignedPosition& d : design.positions) {
    EXPECT_EQ(CheckDesignConstraints(rig, d.coverage.axes, options), "");
    for (const auto& [name, angle] : d.coverage.axes) {
      const geometry::RotationAxis* axis = rig.FindAxis(name);
      ASSERT_NE(axis, nullptr);
      EXPECT_GE(angle, axis->min);
      EXPECT_LE(angle, axis->max);
    }
    (d.coverage.theta_h_min > 2 * kDegree ? off_specular : mirror)++;
  }
  EXPECT_GE(off_specular, 2);
  EXPECT_GE(mirror, 1);
  const CoverageMap mirror_map = ComputeCoverage(rig, MirrorPlan(), {});
  EXPECT_GT(design.covered_fraction, mirror_map.covered_fraction);
  const CoverageMap designed_map = ComputeCoverage(rig, design.Positions(), {});
  EXPECT_GT(designed_map.theta_h_fraction, 2 * mirror_map.theta_h_fraction);
  // Deterministic: the same rig and request give the same plan (a resumed session relies on it).
  const PlanDesign again = DesignPlan(rig, options);
  EXPECT_EQ(again.Positions(), design.Positions());
}

// The prior's objective (prior_objective.h) against the coverage design of the same rig: the
// plan chosen for the prior must reconstruct the training materials, each left out of the
// covariance that judges it, better than the coverage plan does.
TEST(DesignerTest, PriorDesignReconstructsLeftOutMaterialsBetterThanTheCoverageDesign) {
  const geometry::RigGeometry rig = DefaultRig();
  DesignOptions options;
  ASSERT_EQ(options.objective, "prior");  // the default
  const auto start = std::chrono::steady_clock::now();
  const PlanDesign design = DesignPlan(rig, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s(%.2f s)\n", design.ToString().c_str(), seconds);
  ASSERT_EQ(design.positions.size(), 6u);
  for (const DesignedPosition& d : design.positions) {
    EXPECT_EQ(CheckDesignConstraints(rig, d.coverage.axes, options), "");
    EXPECT_GT(d.prior_gain, 0) << "every position lowers the expected error";
  }
  EXPECT_LT(design.expected_rms, 0.5 * design.prior_only_rms);

  DesignOptions coverage_options;
  coverage_options.objective = "coverage";
  const PlanDesign coverage_design = DesignPlan(rig, coverage_options);
  const PriorObjective objective(prior::DefaultPrior(), options.prior_components,
                                 options.search_grid.samples_per_side);
  const auto loo = [&](const PlanDesign& d) {
    Eigen::MatrixXd total = Eigen::MatrixXd::Zero(objective.components(), objective.components());
    for (const auto& axes : d.Positions()) total += objective.Information(rig, axes);
    return objective.RmsPerNode(objective.LeaveOneOutError(total));
  };
  EXPECT_NEAR(loo(design), design.leave_one_out_rms, 1e-9);
  EXPECT_LT(loo(design), loo(coverage_design));
  std::printf("leave-one-material-out RMS per node: prior design %.4f, coverage design %.4f\n",
              loo(design), loo(coverage_design));
  EXPECT_EQ(DesignPlan(rig, options).Positions(), design.Positions());  // deterministic
}

TEST(DesignerTest, ValidationPositionsComeAfterTheFittedOnes) {
  DesignOptions options;
  options.count = 3;
  options.validation = 2;
  const PlanDesign design = DesignPlan(DefaultRig(), options);
  ASSERT_EQ(design.positions.size(), 5u);
  EXPECT_EQ(design.Validation(), (std::vector<bool>{false, false, false, true, true}));
}

TEST(DesignerTest, RequestErrorsNameFileLineAndColumn) {
  const auto error = [](const std::string& yaml) {
    try {
      ParseDesignRequest(LoadYamlString(yaml, "plan.yaml").Required("design"));
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("design:\n  count: 25\n").find("plan.yaml:2:"), std::string::npos);
  EXPECT_NE(error("design:\n  count: 6\n  budget: 3\n").find("plan.yaml:"), std::string::npos);
  EXPECT_NE(error("design:\n  max_candidates: 5000000\n").find("plan.yaml:2:"), std::string::npos);
  const DesignOptions o = ParseDesignRequest(
      LoadYamlString("design: {count: 4, validation: 1}\n", "p").Required("design"));
  EXPECT_EQ(o.count, 4);
  EXPECT_EQ(o.validation, 1);
}

}  // namespace
}  // namespace brdfrig::coverage
