// three.js (the npm package pinned in tests/consumers/package.json: GLTFLoader and
// MeshPhysicalMaterial) reads `brdfrig export`'s .glb in headless Chromium (software WebGL) and
// renders its sphere in the consumer scene (consumer_scene.h); brdfrig's renderer draws the same
// gltf material. The file is read right when three.js's material holds the exported numbers and
// its picture matches brdfrig's to >= 35 dB in linear radiance with the two terms three.js adds
// to the glTF BRDF taken out (the "spec" picture of three_render.mjs). With them in (three.js as
// shipped) the figure is printed and recorded, not required: those terms are three.js's choices
// (docs/gltf.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "brdf/gltf_model.h"
#include "tests/common/run_brdfrig.h"
#include "tests/consumers/consumer_scene.h"
#include "tests/consumers/export_gltf.h"

namespace brdfrig::testing {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string name;
  brdf::GltfParams params;
};

std::vector<Case> Cases() {
  std::vector<Case> cases;
  brdf::GltfParams plastic;  // a rough dielectric: the diffuse and the (1 − F) weighting
  plastic.base_color = {0.55, 0.2, 0.08};
  plastic.roughness = 0.6;
  cases.push_back({"rough_plastic", plastic});
  brdf::GltfParams glossy = plastic;  // a narrow lobe: the highlight's shape and height
  glossy.base_color = {0.05, 0.12, 0.4};
  glossy.roughness = 0.25;
  cases.push_back({"glossy_paint", glossy});
  brdf::GltfParams gold;  // a metal: f0 is the base colour
  gold.base_color = {0.95, 0.7, 0.3};
  gold.metallic = 1;
  gold.roughness = 0.35;
  cases.push_back({"gold", gold});
  brdf::GltfParams coated;  // both extensions away from their defaults, half metallic
  coated.base_color = {0.3, 0.5, 0.3};
  coated.metallic = 0.4;
  coated.roughness = 0.45;
  coated.ior = 1.8;
  coated.specular = 0.7;
  coated.specular_color = {1.0, 0.8, 0.6};
  cases.push_back({"coated_ior_specular", coated});
  return cases;
}

class ThreeJsTest : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    if (!HaveProgram("node") || !HaveProgram("chromium")) {
      GTEST_SKIP() << "needs node and chromium (scripts/setup.sh installs them)";
    }
    ASSERT_TRUE(fs::exists(ConsumersDir() / "node_modules" / "three"))
        << "three.js is missing: run scripts/setup.sh (npm ci in tests/consumers)";
    dir_ = fs::temp_directory_path() / ("three_js_" + GetParam().name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  nlohmann::json RenderWithThree(const fs::path& glb) {
    const fs::path out = dir_ / "three.json";
    const std::string command = "bash '" + (ConsumersDir() / "three_render.sh").string() + "' '" +
                                glb.string() + "' '" + out.string() + "' '" + view_.Query() +
                                "' 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string log;
    char buffer[4096];
    while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) log.append(buffer, n);
    const int status = ::pclose(pipe);
    EXPECT_EQ(status, 0) << log;
    std::ifstream in(out);
    if (!in) return nullptr;
    return nlohmann::json::parse(in);
  }

  ConsumerView view_;
  fs::path dir_;
};

TEST_P(ThreeJsTest, ReadsTheExportedMaterialAndRendersItAsBrdfrigDoes) {
  const Case& c = GetParam();
  CommandResult exported;
  const fs::path glb = ExportGltfMaterial(c.params, dir_, c.name, &exported);
  ASSERT_EQ(exported.status, 0) << exported.output;

  const nlohmann::json three = RenderWithThree(glb);
  ASSERT_FALSE(three.is_null());
  // What three.js made of the file: the exported numbers, on its physical material.
  const nlohmann::json& m = three.at("material");
  EXPECT_EQ(m.at("type"), "MeshPhysicalMaterial");
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(m.at("color")[i].get<double>(), c.params.base_color[i], 1e-6) << "channel " << i;
    EXPECT_NEAR(m.at("specularColor")[i].get<double>(), c.params.specular_color[i], 1e-6);
  }
  EXPECT_NEAR(m.at("metalness").get<double>(), c.params.metallic, 1e-6);
  EXPECT_NEAR(m.at("roughness").get<double>(), c.params.roughness, 1e-6);
  EXPECT_NEAR(m.at("ior").get<double>(), c.params.ior, 1e-6);
  EXPECT_NEAR(m.at("specularIntensity").get<double>(), c.params.specular, 1e-6);

  const cv::Mat ours = RenderWithBrdfrig(brdf::GltfModel(c.params), view_);
  const cv::Mat mask = SphereInterior(view_);
  const evaluate::PsnrResult strict = CompareLinear(ours, ThreeJsImage(three, "spec"), mask);
  const evaluate::PsnrResult as_shipped = CompareLinear(ours, ThreeJsImage(three, "shipped"), mask);
  std::printf(
      "three.js r%s vs brdfrig, %s: %.1f dB (glTF BRDF), %.1f dB (three.js as shipped)"
      " over %ld pixels; %s\n",
      three.at("three").get<std::string>().c_str(), c.name.c_str(), strict.psnr_db,
      as_shipped.psnr_db, strict.pixels, strict.protocol.c_str());
  RecordProperty("psnr_spec_db", std::to_string(strict.psnr_db));
  RecordProperty("psnr_shipped_db", std::to_string(as_shipped.psnr_db));
  EXPECT_GE(strict.psnr_db, 35.0) << strict.Report();
  EXPECT_GT(strict.pixels, view_.width * view_.height / 2);
}

INSTANTIATE_TEST_SUITE_P(Materials, ThreeJsTest, ::testing::ValuesIn(Cases()),
                         [](const auto& test) { return test.param.name; });

}  // namespace
}  // namespace brdfrig::testing
