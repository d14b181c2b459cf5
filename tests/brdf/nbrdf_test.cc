// The measured materials (nbrdf fits): forward pass against the published reference values,
// directional albedo against the reference quadrature, loader errors, the by-name lookup.
#include "brdf/nbrdf.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "brdf/analytic.h"
#include "brdf/brdf_file.h"
#include "brdf/metrics.h"
#include "brdf/nbrdf_library.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

constexpr double kDeg = M_PI / 180;

Vec3 Direction(double theta_deg, double phi_deg) {
  const double t = theta_deg * kDeg, p = phi_deg * kDeg;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// Rows of a reference table: material name, then numbers. '#' lines are comments.
std::vector<std::pair<std::string, std::vector<double>>> ReadTable(const std::string& file) {
  std::ifstream in(NbrdfDirectory() / file);
  EXPECT_TRUE(in) << file;
  std::vector<std::pair<std::string, std::vector<double>>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::pair<std::string, std::vector<double>> row;
    fields >> row.first;
    for (double x; fields >> x;) row.second.push_back(x);
    rows.push_back(row);
  }
  return rows;
}

std::string Layers(const std::string& bias0) {
  const std::string row6 = "[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]";
  std::string w1 = "[", w2 = "[", w3 = "[";
  for (int i = 0; i < 6; ++i) w1 += (i ? "," : "") + row6;
  for (int i = 0; i < 21; ++i) w2 += (i ? "," : "") + row6;
  for (int i = 0; i < 21; ++i) w3 += std::string(i ? "," : "") + "[0,0,0]";
  return R"({"weights":)" + w1 + R"(],"bias":)" + bias0 + R"(,"activation":"relu"},)" +
         R"({"weights":)" + w2 + R"(],"bias":)" + row6 + R"(,"activation":"relu"},)" +
         R"({"weights":)" + w3 + R"(],"bias":[0.1,0.2,0.3],"activation":"exp_minus_one"})";
}

std::string Document(const std::string& bias0) {
  return R"({"format":"nbrdf-mlp","version":1,"name":"t","layers":[)" + Layers(bias0) + "]}";
}

TEST(NbrdfTest, ForwardPassMatchesTheReferenceValuesOfEveryMaterial) {
  const auto rows = ReadTable("reference.tsv");
  ASSERT_EQ(rows.size(), 80u * 5);
  std::map<std::string, std::shared_ptr<NeuralBrdf>> materials;
  double worst = 0;
  for (const auto& [name, x] : rows) {
    ASSERT_EQ(x.size(), 7u);
    if (!materials.count(name)) {
      materials[name] = std::make_shared<NeuralBrdf>(ReadNbrdfMaterial(name));
    }
    const Rgb f =
        materials[name]->Eval(Direction(x[0], x[1]), Direction(x[2], x[3]), Vec3::UnitZ());
    for (int c = 0; c < 3; ++c) {
      const double rel = std::abs(f[c] - x[4 + c]) / std::max(std::abs(x[4 + c]), 1e-12);
      worst = std::max(worst, rel);
      EXPECT_LT(rel, 1e-5) << name << " row " << x[0] << "," << x[1] << "," << x[2] << "," << x[3]
                           << " channel " << c << ": " << f[c] << " vs " << x[4 + c];
    }
  }
  EXPECT_EQ(materials.size(), 80u);
  std::cout << "worst relative error against reference.tsv: " << worst << "\n";
}

TEST(NbrdfTest, ValueDoesNotDependOnTheFrameOrTheSurfaceOrientation) {
  const NeuralBrdf brass = ReadNbrdfMaterial("brass");
  const Vec3 l = Direction(40, 10), v = Direction(25, 200);
  const Rgb local = brass.Eval(l, v, Vec3::UnitZ());
  // Rotating everything about the normal (isotropy) or tilting the surface with the directions
  // (world frame) must not change the value.
  const Eigen::AngleAxisd spin(0.7, Vec3::UnitZ());
  const Eigen::AngleAxisd tilt(-2.1, Vec3(0.3, -1, 0.2).normalized());
  EXPECT_LT(((brass.Eval(spin * l, spin * v, Vec3::UnitZ()) - local).abs() / local).maxCoeff(),
            1e-12);
  EXPECT_LT(
      ((brass.Eval(tilt * l, tilt * v, tilt * Vec3::UnitZ()) - local).abs() / local).maxCoeff(),
      1e-12);
  EXPECT_EQ(brass.Eval(Direction(95, 0), v, Vec3::UnitZ()).maxCoeff(), 0);
  EXPECT_EQ(brass.Eval(l, Direction(90.5, 0), Vec3::UnitZ()).maxCoeff(), 0);
  EXPECT_TRUE(brass.Eval(Vec3::UnitZ(), Vec3::UnitZ(), Vec3::UnitZ()).isFinite().all());
  EXPECT_EQ(brass.Name(), "nbrdf(brass)");
  EXPECT_EQ(brass.database(), "merl");
}

TEST(NbrdfTest, DirectionalAlbedoOfEveryMaterialMatchesTheReferenceQuadrature) {
  // albedo.tsv is printed to 4 decimals: half of the last digit is allowed on top of the 2 %.
  const auto rows = ReadTable("albedo.tsv");
  ASSERT_EQ(rows.size(), 80u * 4);
  std::map<std::string, double> worst;
  for (const auto& [name, x] : rows) {
    const NeuralBrdf brdf = ReadNbrdfMaterial(name);
    const Rgb albedo = DirectionalAlbedo(brdf, x[0] * kDeg);
    for (int c = 0; c < 3; ++c) {
      const double error = std::abs(albedo[c] - x[1 + c]);
      worst[name] = std::max(worst[name], error / x[1 + c]);
      EXPECT_LE(error, 0.02 * x[1 + c] + 5e-5)
          << name << " at " << x[0] << "° channel " << c << ": " << albedo[c] << " vs " << x[1 + c];
    }
  }
  for (const auto& [name, w] : worst) std::cout << name << " worst relative " << w << "\n";
}

TEST(NbrdfTest, AlbedoQuadratureConvergesForSharpLobes) {
  // A near-mirror GGX (alpha 0.01: lobe ~0.6°) and the sharpest measured metal: the default
  // resolution agrees with a 4× finer one.
  const Ggx mirror({Rgb::Zero(), Rgb::Constant(0.9), 0.01});
  const NeuralBrdf chrome = ReadNbrdfMaterial("chrome-steel");
  for (const Brdf* brdf : std::initializer_list<const Brdf*>{&mirror, &chrome}) {
    for (double theta : {0.0, 0.5, 1.0, 1.3}) {
      const Rgb coarse = DirectionalAlbedo(*brdf, theta);
      const Rgb fine = DirectionalAlbedo(*brdf, theta, {128, 256});
      EXPECT_LT(((coarse - fine).abs() / fine).maxCoeff(), 2e-3) << brdf->Name() << " " << theta;
    }
  }
}

TEST(NbrdfTest, LoaderNamesTheFileAndTheFieldThatIsWrong) {
  const std::string ok_bias = "[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]";
  const NeuralBrdf ok = NeuralBrdf::Parse(Document(ok_bias), "ok.json");
  EXPECT_NEAR(ok.EvalLocal(Direction(10, 0), Direction(20, 180))[2], std::expm1(0.3), 1e-15);

  auto message = [](const std::string& text) {
    try {
      NeuralBrdf::Parse(text, "m.json");
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  using ::testing::HasSubstr;
  EXPECT_THAT(message("{"), HasSubstr("m.json"));
  EXPECT_THAT(message(R"({"format":"brdfrig-slices","version":1})"), HasSubstr("format"));
  EXPECT_THAT(message(R"({"format":"nbrdf-mlp","version":2})"), HasSubstr("version"));
  EXPECT_THAT(message(Document("[0,0]")), HasSubstr("layers[0].bias: expected an array of 21"));
  EXPECT_THAT(message(Document(R"([0,0,0,0,0,0,0,0,0,0,"x",0,0,0,0,0,0,0,0,0,0])")),
              HasSubstr("layers[0].bias[10]: expected a number"));
  EXPECT_THAT(message(Document("[0,0,0,0,0,0,0,0,0,0,1e999,0,0,0,0,0,0,0,0,0,0]")),
              HasSubstr("m.json"));  // out of range: refused by the parser
  std::string relu3 = Document(ok_bias);
  relu3.replace(relu3.find("exp_minus_one"), 13, "relu");
  EXPECT_THAT(message(relu3), HasSubstr("layers[2].activation: expected \"exp_minus_one\""));
  std::string two_layers = R"({"format":"nbrdf-mlp","version":1,"name":"t","layers":[]})";
  EXPECT_THAT(message(two_layers), HasSubstr("layers: expected 3 layers"));
}

TEST(NbrdfTest, MaterialsAreFoundByNameAndByFile) {
  const std::vector<std::string> names = NbrdfMaterialNames();
  EXPECT_EQ(names.size(), 80u);
  EXPECT_EQ(NbrdfStudyMaterialNames().size(), 27u);
  EXPECT_THAT(names, ::testing::Contains("gold-metallic-paint"));
  try {
    NbrdfMaterialPath("../nbrdf/brass");
    ADD_FAILURE() << "a path is not a name";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("gold-metallic-paint"));
  }
  // The generic loader tells an nbrdf file from a brdfrig model by its format.
  const auto brdf = LoadBrdfFile(NbrdfMaterialPath("steel"));
  EXPECT_EQ(brdf->Name(), "nbrdf(steel)");
}

}  // namespace
}  // namespace brdfrig::brdf
