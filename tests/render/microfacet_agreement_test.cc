// The GLSL microfacet rungs (shaders/microfacet_model.glsl) against the CPU reference
// (brdf::MicrofacetModel::Eval, double) on a dense grid of light and view directions: every
// incidence and exit angle up to 89.9°, relative azimuths 0…180°, the exact mirror direction and
// its close neighbourhood (where sharp lobes live), and directions a hair above the horizon.
// Runs on llvmpipe in CI.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "brdf/microfacet_model.h"
#include "brdf/microfacet_terms.h"
#include "render/gl_context.h"
#include "render/gpu_material.h"
#include "render/material_probe.h"

namespace brdfrig::render {
namespace {

constexpr double kDeg = M_PI / 180;

// float32 evaluation of a model whose values span ~10 decades: relative error where the value
// is meaningful, absolute below kFloor (1/sr; a dark diffuse is 0.01/pi ≈ 3e-3).
constexpr double kTolerance = 1e-4;
constexpr double kFloor = 1e-4;

Eigen::Vector3d Direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

struct DirectionGrid {
  std::vector<Eigen::Vector3f> light, view;  // in the frame where the normal is +z
  void Add(const Eigen::Vector3d& l, const Eigen::Vector3d& v) {
    light.push_back(l.cast<float>());
    view.push_back(v.cast<float>());
  }
};

DirectionGrid MakeGrid(bool horizon) {
  DirectionGrid grid;
  // Angles from 0 to 89.9°, denser towards grazing.
  const int n_theta = 48, n_phi = 25;
  std::vector<double> thetas;
  for (int i = 0; i < n_theta; ++i) {
    const double u = static_cast<double>(i) / (n_theta - 1);
    thetas.push_back((1 - (1 - u) * (1 - u)) * 89.9 * kDeg);
  }
  for (double ti : thetas) {
    const Eigen::Vector3d l = Direction(ti, 0.3);
    for (double to : thetas) {
      for (int k = 0; k < n_phi; ++k) grid.Add(l, Direction(to, 0.3 + M_PI * k / (n_phi - 1)));
    }
    // The exact mirror direction (h = n bit for bit) and its neighbourhood.
    const Eigen::Vector3d mirror(-l.x(), -l.y(), l.z());
    grid.Add(l, mirror);
    for (double d : {1e-5, 1e-4, 1e-3, 3e-3, 0.01, 0.03, 0.1}) {
      const double to = std::min(ti + d, 89.9 * kDeg);
      grid.Add(l, Direction(to, 0.3 + M_PI));
      grid.Add(l, Direction(ti, 0.3 + M_PI + d));
    }
  }
  // A hair above the horizon (cos 1e-6 and 1e-20): finite, as on the CPU.
  for (double z : {1e-6, 1e-20}) {
    if (!horizon) break;
    const Eigen::Vector3d l = Eigen::Vector3d(1, 0, z).normalized();
    for (double to : thetas) {
      grid.Add(l, Direction(to, M_PI));
      grid.Add(Direction(to, 0.5), l);
    }
  }
  return grid;
}

struct Agreement {
  double max_relative = 0;
  Eigen::Vector3d light_at = Eigen::Vector3d::Zero(), view_at = Eigen::Vector3d::Zero();
  int checked = 0;
};

// Max over the grid of |gpu − cpu| / max(|cpu|, kFloor), with the grid rotated so that the
// normal is `normal`. The CPU evaluates at exactly the float vectors the GPU saw.
Agreement Compare(const brdf::MicrofacetModel& model, const DirectionGrid& grid,
                  const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), normal);
  const Eigen::Vector3f n = normal.cast<float>();
  const int width = 512;
  const int count = static_cast<int>(grid.light.size());
  const int height = (count + width - 1) / width;
  cv::Mat light(height, width, CV_32FC3, cv::Scalar(0, 0, 1)),
      view(height, width, CV_32FC3, cv::Scalar(0, 0, 1));
  std::vector<Eigen::Vector3f> l_used(count), v_used(count);
  for (int i = 0; i < count; ++i) {
    l_used[i] = (rotation * grid.light[i].cast<double>()).cast<float>();
    v_used[i] = (rotation * grid.view[i].cast<double>()).cast<float>();
    light.at<cv::Vec3f>(i / width, i % width) = {l_used[i].x(), l_used[i].y(), l_used[i].z()};
    view.at<cv::Vec3f>(i / width, i % width) = {v_used[i].x(), v_used[i].y(), v_used[i].z()};
  }
  const std::unique_ptr<GpuMaterial> material = GpuMaterial::Microfacet(model);
  const cv::Mat gpu = EvalMaterialOnGpu(*material, light, view, n);
  Agreement worst;
  for (int i = 0; i < count; ++i) {
    const brdf::Rgb cpu =
        model.Eval(l_used[i].cast<double>(), v_used[i].cast<double>(), n.cast<double>());
    const cv::Vec3f g = gpu.at<cv::Vec3f>(i / width, i % width);
    for (int c = 0; c < 3; ++c) {
      const double rel = std::abs(g[c] - cpu[c]) / std::max(std::abs(cpu[c]), kFloor);
      if (!(rel <= worst.max_relative)) {
        worst.max_relative = rel;
        worst.light_at = grid.light[i].cast<double>();
        worst.view_at = grid.view[i].cast<double>();
      }
      ++worst.checked;
    }
  }
  return worst;
}

double AngleDeg(const Eigen::Vector3d& a) { return std::acos(std::clamp(a.z(), -1.0, 1.0)) / kDeg; }

class MicrofacetAgreementTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = CreateHeadlessContext().release();
    grid_ = new DirectionGrid(MakeGrid(true));
    // Rotated, a cosine of 1e-6 falls below float's resolution and the float and double sides
    // of the horizon cut differ: the tilted grid stops at 89.9°.
    tilted_grid_ = new DirectionGrid(MakeGrid(false));
  }
  static void TearDownTestSuite() {
    delete grid_;
    delete tilted_grid_;
    delete context_;
  }
  // Compares, prints and records the worst error under `name`.
  static double Check(const std::string& name, const brdf::MicrofacetModel& model,
                      const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
    const Agreement a = Compare(model, normal.z() == 1 ? *grid_ : *tilted_grid_, normal);
    RecordProperty("max_relative_" + name, std::to_string(a.max_relative));
    std::printf("%s: max relative error %.3g over %d values (at theta_in %.4f°, theta_out %.4f°)\n",
                name.c_str(), a.max_relative, a.checked, AngleDeg(a.light_at), AngleDeg(a.view_at));
    return a.max_relative;
  }
  static GlContext* context_;
  static DirectionGrid* grid_;
  static DirectionGrid* tilted_grid_;
};
GlContext* MicrofacetAgreementTest::context_ = nullptr;
DirectionGrid* MicrofacetAgreementTest::grid_ = nullptr;
DirectionGrid* MicrofacetAgreementTest::tilted_grid_ = nullptr;

brdf::MicrofacetModelParams Analytic(brdf::Distribution d, double alpha) {
  brdf::MicrofacetModelParams p;
  p.distribution = d;
  p.alpha = alpha;
  p.diffuse = brdf::Rgb(0.1, 0.05, 0.03);
  p.f0 = brdf::Rgb(0.9, 0.6, 0.35);
  return p;
}

// A table shaped like a broad peak plus a narrow one (not any analytic D), with a GGX tail.
brdf::MicrofacetModelParams Table(int knots, double max_theta_h) {
  brdf::MicrofacetModelParams p;
  p.distribution = brdf::Distribution::kTable;
  p.alpha = 0.25;
  p.shadowing_alpha = 0.15;
  p.max_theta_h = max_theta_h;
  p.diffuse = brdf::Rgb(0.2, 0.1, 0.05);
  p.f0 = brdf::Rgb(0.04, 0.05, 0.06);
  p.fresnel_knots = {0, -0.05, 0.1, -0.2, 0.3};
  for (int k = 0; k < knots; ++k) {
    const double t = brdf::microfacet::TableKnotThetaH(k, knots, max_theta_h);
    p.log_d.push_back(std::log(50 * std::exp(-t * t / 0.002) + 2 * std::exp(-t * t / 0.1) + 1e-3));
  }
  return p;
}

TEST_F(MicrofacetAgreementTest, GgxAgreesToFloatTolerance) {
  for (double alpha : {0.02, 0.1, 0.4, 1.0}) {
    const brdf::MicrofacetModel model(Analytic(brdf::Distribution::kGgx, alpha));
    EXPECT_LT(Check("ggx_alpha_" + std::to_string(alpha), model), kTolerance);
  }
}

TEST_F(MicrofacetAgreementTest, BeckmannAgreesToFloatTolerance) {
  for (double alpha : {0.02, 0.1, 0.4, 1.0}) {
    const brdf::MicrofacetModel model(Analytic(brdf::Distribution::kBeckmann, alpha));
    EXPECT_LT(Check("beckmann_alpha_" + std::to_string(alpha), model), kTolerance);
  }
}

TEST_F(MicrofacetAgreementTest, TableWithTailAndFresnelKnotsAgreesToFloatTolerance) {
  const brdf::MicrofacetModel model(Table(32, 0.6));
  EXPECT_LT(Check("microfacet_32_knots", model), kTolerance);
}

TEST_F(MicrofacetAgreementTest, TableOverTheWholeRangeWithMostKnotsAgrees) {
  brdf::MicrofacetModelParams p = Table(kMaxTableKnots, M_PI / 2);
  p.fresnel_knots = {0.1};
  EXPECT_LT(Check("microfacet_256_knots_no_tail", brdf::MicrofacetModel(p)), kTolerance);
  p = Table(2, 0.05);
  p.fresnel_knots.clear();
  EXPECT_LT(Check("microfacet_2_knots", brdf::MicrofacetModel(p)), kTolerance);
}

TEST_F(MicrofacetAgreementTest, EveryKindAgreesForATiltedNormal) {
  const Eigen::Vector3d normal = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  EXPECT_LT(
      Check("ggx_tilted", brdf::MicrofacetModel(Analytic(brdf::Distribution::kGgx, 0.1)), normal),
      kTolerance);
  EXPECT_LT(Check("beckmann_tilted",
                  brdf::MicrofacetModel(Analytic(brdf::Distribution::kBeckmann, 0.1)), normal),
            kTolerance);
  EXPECT_LT(Check("microfacet_tilted", brdf::MicrofacetModel(Table(32, 0.6)), normal), kTolerance);
}

TEST_F(MicrofacetAgreementTest, ExtremeRoughnessStaysFinite) {
  // alpha at the limits Validate allows: a 3e7/sr mirror spike and a nearly flat lobe.
  for (double alpha : {1e-4, 4.0}) {
    for (brdf::Distribution d : {brdf::Distribution::kGgx, brdf::Distribution::kBeckmann}) {
      const brdf::MicrofacetModel model(Analytic(d, alpha));
      EXPECT_LT(
          Check(std::string(brdf::DistributionName(d)) + "_alpha_" + std::to_string(alpha), model),
          1e-3);
    }
  }
}

}  // namespace
}  // namespace brdfrig::render
