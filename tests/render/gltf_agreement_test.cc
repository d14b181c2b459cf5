// The GLSL gltf kind (shaders/gltf_model.glsl) against the CPU reference (brdf::GltfModel::Eval,
// double) on the dense grid of tests/render/direction_grid.h: every incidence and exit angle up
// to 89.9°, the mirror direction and its neighbourhood, directions a hair above the horizon;
// dielectric, metal and mixed materials from nearly mirror-like to fully rough. llvmpipe in CI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "brdf/gltf_model.h"
#include "render/gl_context.h"
#include "render/gpu_material.h"
#include "tests/render/direction_grid.h"

namespace brdfrig::render {
namespace {

using testing::Agreement;
using testing::CompareOnGrid;
using testing::DirectionGrid;
using testing::MakeGrid;

// As for the microfacet rungs (microfacet_agreement_test.cc): relative error where the value is
// meaningful, absolute below kFloor (1/sr).
constexpr double kTolerance = 1e-4;
constexpr double kFloor = 1e-4;

brdf::GltfParams Material(double metallic, double roughness) {
  brdf::GltfParams p;
  p.base_color = brdf::Rgb(0.8, 0.45, 0.1);
  p.metallic = metallic;
  p.roughness = roughness;
  p.ior = 1.6;
  p.specular = 0.9;
  p.specular_color = brdf::Rgb(1.0, 0.8, 0.5);
  return p;
}

class GltfAgreementTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = CreateHeadlessContext().release();
    grid_ = new DirectionGrid(MakeGrid(true));
    tilted_grid_ = new DirectionGrid(MakeGrid(false));
  }
  static void TearDownTestSuite() {
    delete grid_;
    delete tilted_grid_;
    delete context_;
  }
  static double Check(const std::string& name, const brdf::GltfParams& params,
                      const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
    const brdf::GltfModel model(params);
    const std::unique_ptr<GpuMaterial> material = GpuMaterial::Gltf(model);
    const Agreement a =
        CompareOnGrid(*material, model, normal.z() == 1 ? *grid_ : *tilted_grid_, normal,
                      [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return kFloor; });
    RecordProperty("max_relative_" + name, std::to_string(a.max_relative));
    std::printf("%s: max relative error %.3g over %d values\n", name.c_str(), a.max_relative,
                a.checked);
    return a.max_relative;
  }
  static GlContext* context_;
  static DirectionGrid* grid_;
  static DirectionGrid* tilted_grid_;
};
GlContext* GltfAgreementTest::context_ = nullptr;
DirectionGrid* GltfAgreementTest::grid_ = nullptr;
DirectionGrid* GltfAgreementTest::tilted_grid_ = nullptr;

TEST_F(GltfAgreementTest, DielectricMetalAndMixAgreeToFloatTolerance) {
  for (double metallic : {0.0, 0.4, 1.0}) {
    for (double roughness : {0.15, 0.5, 1.0}) {
      EXPECT_LT(Check("gltf_m" + std::to_string(metallic) + "_r" + std::to_string(roughness),
                      Material(metallic, roughness)),
                kTolerance);
    }
  }
}

TEST_F(GltfAgreementTest, ClampedSpecularColourAndNoSpecularAgree) {
  brdf::GltfParams p = Material(0.0, 0.3);
  p.ior = 3;
  p.specular_color = brdf::Rgb(5, 1, 0.2);  // f0 clamps to 1 in red
  EXPECT_LT(Check("gltf_clamped_f0", p), kTolerance);
  p.specular = 0;
  EXPECT_LT(Check("gltf_no_specular", p), kTolerance);
}

TEST_F(GltfAgreementTest, AgreesForATiltedNormal) {
  EXPECT_LT(Check("gltf_tilted", Material(0.3, 0.3), Eigen::Vector3d(0.3, -0.5, 0.8).normalized()),
            kTolerance);
}

}  // namespace
}  // namespace brdfrig::render
