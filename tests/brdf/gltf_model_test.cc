// The `gltf` kind: the glTF 2.0 metal-rough BRDF (Appendix B) with KHR_materials_ior and
// KHR_materials_specular, checked the way pbrt checks a BRDF (reciprocity, energy, the white
// furnace) and against the specification's formulas written out by hand at chosen angles.
#include "brdf/gltf_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "brdf/material_file.h"
#include "brdf/metrics.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

using ::testing::HasSubstr;

const Vec3 kN = Vec3::UnitZ();

GltfParams Coloured() {
  GltfParams p;
  p.base_color = Rgb(0.7, 0.4, 0.2);
  p.metallic = 0.3;
  p.roughness = 0.45;
  p.ior = 1.8;
  p.specular = 0.7;
  p.specular_color = Rgb(1.0, 0.6, 0.3);
  return p;
}

Vec3 Direction(double theta, double phi) {
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// The specification's formulas, written out again without brdf/gltf_terms.h.
Rgb ByHand(const GltfParams& p, const Vec3& l, const Vec3& v) {
  const Vec3 h = (l + v).normalized();
  const double nl = l.z(), nv = v.z(), nh = h.z(), vh = v.dot(h);
  const double a = p.roughness * p.roughness, a2 = a * a;
  const double d = a2 / (M_PI * std::pow(nh * nh * (a2 - 1) + 1, 2));
  const double vis =
      1 / ((nl + std::sqrt(a2 + (1 - a2) * nl * nl)) * (nv + std::sqrt(a2 + (1 - a2) * nv * nv)));
  const double x = std::pow(1 - vh, 5);
  const double ior_f0 = std::pow((p.ior - 1) / (p.ior + 1), 2);
  Rgb fr;
  for (int c = 0; c < 3; ++c) {
    const double f0 = std::min(ior_f0 * p.specular_color[c], 1.0);
    fr[c] = f0 + (1 - f0) * x;
  }
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    const double dielectric =
        (1 - p.specular * fr.maxCoeff()) * p.base_color[c] / M_PI + p.specular * fr[c] * d * vis;
    const double metal = (p.base_color[c] + (1 - p.base_color[c]) * x) * d * vis;
    out[c] = (1 - p.metallic) * dielectric + p.metallic * metal;
  }
  return out;
}

TEST(GltfModelTest, AgreesWithTheSpecificationsFormulasAtChosenAngles) {
  const GltfModel model(Coloured());
  for (const auto& [ti, to, phi] : {std::tuple{0.0, 0.0, 0.0},
                                    {0.5, 0.5, M_PI},
                                    {0.3, 1.2, 2.0},
                                    {1.4, 0.2, 0.7},
                                    {1.5, 1.5, M_PI}}) {
    const Vec3 l = Direction(ti, 0), v = Direction(to, phi);
    const Rgb expected = ByHand(Coloured(), l, v);
    const Rgb got = model.Eval(l, v, kN);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(got[c], expected[c], 1e-12 * std::max(1.0, expected[c])) << ti << " " << to;
    }
  }
}

TEST(GltfModelTest, NormalIncidenceHasItsClosedForm) {
  // l = v = n: D = 1/(pi alpha²), V = 1/4, Schlick weight 0.
  const GltfParams p = Coloured();
  const double alpha = p.roughness * p.roughness;
  const double spec = 1 / (4 * M_PI * alpha * alpha);
  const Rgb f0 = p.DielectricF0();
  const Rgb got = GltfModel(p).Eval(kN, kN, kN);
  for (int c = 0; c < 3; ++c) {
    const double dielectric =
        (1 - p.specular * f0.maxCoeff()) * p.base_color[c] / M_PI + p.specular * f0[c] * spec;
    const double metal = p.base_color[c] * spec;
    EXPECT_NEAR(got[c], (1 - p.metallic) * dielectric + p.metallic * metal, 1e-12);
  }
}

TEST(GltfModelTest, DefaultExtensionsGiveTheCoreSpecificationsDielectric) {
  // ior 1.5, specular 1, specularColor white: f0 = 0.04 and mix(diffuse, specular, F).
  GltfParams p;
  p.base_color = Rgb(0.5, 0.3, 0.2);
  p.roughness = 0.3;
  const GltfModel model(p);
  const Vec3 l = Direction(0.9, 0), v = Direction(0.4, 2.5);
  const Vec3 h = (l + v).normalized();
  const double fr = 0.04 + 0.96 * std::pow(1 - v.dot(h), 5);
  GltfParams spec_only = p;
  spec_only.base_color = Rgb::Zero();
  const double specular_brdf = GltfModel(spec_only).Eval(l, v, kN)[0] / fr;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(model.Eval(l, v, kN)[c], (1 - fr) * p.base_color[c] / M_PI + fr * specular_brdf,
                1e-12);
  }
}

TEST(GltfModelTest, SpecularZeroIsLambertian) {
  GltfParams p = Coloured();
  p.metallic = 0;
  p.specular = 0;
  const GltfModel model(p);
  for (double t : {0.1, 0.8, 1.4}) {
    const Rgb f = model.Eval(Direction(t, 0), Direction(0.6, 1.0), kN);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], p.base_color[c] / M_PI, 1e-15);
  }
}

TEST(GltfModelTest, IsReciprocal) {
  EXPECT_LT(ReciprocityError(GltfModel(Coloured()), {16, 32}), 1e-10);
}

TEST(GltfModelTest, IsNonNegativeFiniteAndZeroBelowTheHorizon) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  const GltfModel model(Coloured());
  for (int i = 0; i < 4000; ++i) {
    const Vec3 l = Vec3(g(rng), g(rng), g(rng)).normalized();
    const Vec3 v = Vec3(g(rng), g(rng), g(rng)).normalized();
    const Rgb f = model.Eval(l, v, kN);
    ASSERT_TRUE(f.isFinite().all());
    ASSERT_GE(f.minCoeff(), 0);
    if (l.z() <= 0 || v.z() <= 0) {
      ASSERT_EQ(f.maxCoeff(), 0);
    }
  }
}

// The white furnace: a white metal and a white dielectric whose specular colour saturates f0
// are the brightest the kind can be; neither may reflect more than it receives. A single-
// scattering microfacet lobe loses energy at high roughness, so the brightest channel also has
// a floor. (The others do not: KHR_materials_specular weights the diffuse by 1 − max_c F, so
// the red f0 of 1 here leaves green and blue only their own, weaker specular.)
TEST(GltfModelTest, WhiteFurnaceAlbedoNeverExceedsOne) {
  for (double roughness : {0.05, 0.3, 0.7, 1.0}) {
    GltfParams metal;
    metal.base_color = Rgb::Ones();
    metal.metallic = 1;
    metal.roughness = roughness;
    GltfParams dielectric;
    dielectric.base_color = Rgb::Ones();
    dielectric.roughness = roughness;
    dielectric.ior = 3;
    dielectric.specular_color = Rgb(4, 2, 1);  // f0 clamps to 1 in red
    for (const GltfParams& p : {metal, dielectric}) {
      for (double theta_in : {0.0, 0.6, 1.1, 1.4}) {
        const Rgb a = DirectionalAlbedo(GltfModel(p), theta_in, {256, 128});
        EXPECT_LE(a.maxCoeff(), 1.0 + 2e-3) << GltfModel(p).Name() << " at " << theta_in;
        EXPECT_GT(a.maxCoeff(), 0.3) << GltfModel(p).Name() << " at " << theta_in;
      }
    }
  }
}

TEST(GltfModelTest, InvalidParametersNameTheField) {
  GltfParams p;
  p.roughness = 0;
  EXPECT_THROW(
      {
        try {
          p.Validate();
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), HasSubstr("roughness = 0; must be finite and in [0.01, 1]"));
          throw;
        }
      },
      Error);
  p = GltfParams();
  p.specular_color[2] = -0.1;
  EXPECT_THROW(p.Validate(), Error);
  p = GltfParams();
  p.ior = 0.9;
  EXPECT_THROW(p.Validate(), Error);
  p = GltfParams();
  p.metallic = std::nan("");
  EXPECT_THROW(p.Validate(), Error);
}

Material GltfExample() {
  Material m;
  m.kind = ModelKind::kGltf;
  m.gltf = Coloured();
  m.gltf_fit = {{"source", "test"}};
  return m;
}

TEST(GltfModelTest, MaterialFileRoundTripsExactly) {
  const Material m = GltfExample();
  const Material r = ParseMaterial(SerializeMaterial(m), "m.json");
  EXPECT_EQ(r.kind, ModelKind::kGltf);
  ASSERT_TRUE(r.gltf.has_value());
  EXPECT_EQ(r.gltf->specular_color[1], m.gltf->specular_color[1]);
  EXPECT_EQ(r.gltf_fit, m.gltf_fit);
  EXPECT_EQ(SerializeMaterial(r), SerializeMaterial(m));
  const Vec3 l = Direction(0.4, 0), v = Direction(0.7, 2.0);
  EXPECT_EQ(r.Model()->Eval(l, v, kN)[2], GltfModel(Coloured()).Eval(l, v, kN)[2]);
  EXPECT_EQ(ParseModelKind("gltf"), ModelKind::kGltf);
}

TEST(GltfModelTest, AnyKindCarriesItsGltfVersion) {
  Material m;
  m.kind = ModelKind::kGgx;
  m.microfacet.distribution = Distribution::kGgx;
  m.gltf = Coloured();
  const Material r = ParseMaterial(SerializeMaterial(m), "m.json");
  EXPECT_EQ(r.kind, ModelKind::kGgx);
  ASSERT_TRUE(r.gltf.has_value());
  EXPECT_EQ(r.gltf->ior, Coloured().ior);
  // Without it nothing is written, so older materials keep their bytes.
  m.gltf.reset();
  EXPECT_EQ(nlohmann::json::parse(SerializeMaterial(m)).count("gltf"), 0u);
}

std::string ErrorOf(const std::string& text) {
  try {
    (void)ParseMaterial(text, "bad.json");
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(GltfModelTest, MaterialFileErrorsNameTheField) {
  nlohmann::json doc = nlohmann::json::parse(SerializeMaterial(GltfExample()));
  doc["gltf"]["metallic"] = 1.5;
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("bad.json: gltf: metallic = 1.5; must be finite"));
  doc = nlohmann::json::parse(SerializeMaterial(GltfExample()));
  doc["gltf"]["base_color"][1] = "x";
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("gltf.base_color: expected finite numbers"));
  doc = nlohmann::json::parse(SerializeMaterial(GltfExample()));
  doc["gltf"].erase("ior");
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("gltf.ior: missing"));
  doc = nlohmann::json::parse(SerializeMaterial(GltfExample()));
  doc.erase("gltf");
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("gltf: missing"));
  doc = nlohmann::json::parse(SerializeMaterial(GltfExample()));
  doc["gltf_fit"] = 3;
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("gltf_fit: expected an object"));
}

}  // namespace
}  // namespace brdfrig::brdf
