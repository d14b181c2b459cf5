// Measured materials as the sample of a scene: named in the scene file, rendered as the BRDF
// says, and a whole simulated capture of the default scene with one.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <fstream>

#include "brdf/nbrdf_library.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "sim/simulate.h"
#include "sim/simulator.h"

namespace brdfrig::sim {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = M_PI / 180.0;

// The shipped default scene at 320×240 with `brdf` as the sample's material.
std::string DefaultSceneWith(const std::string& brdf) {
  std::string text = ReadFileToString(fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/ggx.yaml");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  replace("resolution: [1600, 1200]", "resolution: [320, 240]");
  replace("brdf: {model: ggx, alpha: 0.1, f0: [0.9, 0.6, 0.35], diffuse: [0.1, 0.05, 0.03]}",
          "brdf: " + brdf);
  replace("supersampling: 4", "supersampling: 2");
  return text;
}

std::string SceneError(const std::string& brdf) {
  try {
    LoadSceneString(DefaultSceneWith(brdf), "scene.yaml");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(NbrdfSceneTest, ASampleNamedByMaterialRendersItsBrdf) {
  const Scene scene =
      LoadSceneString(DefaultSceneWith("{model: nbrdf, name: gold-metallic-paint}"), "s.yaml");
  EXPECT_EQ(scene.sample.brdf->Name(), "nbrdf(gold-metallic-paint)");
  const Simulator simulator(scene.Ideal());
  const geometry::AxisPositions p = {{"camera_arm", 30 * kDegree}, {"light_arm", -20 * kDegree}};
  const cv::Mat radiance = simulator.RenderRadiance(p);
  ASSERT_EQ(radiance.cols, 320);
  EXPECT_TRUE(cv::checkRange(radiance));
  // The pixel at the image centre sees the sample near the origin: its radiance is the
  // material's BRDF times the irradiance there.
  const TrueGeometry g = simulator.GeometryAt(p);
  const cv::Point2d centre(160, 120);
  const geometry::Vec3 ray =
      geometry::PixelRayInWorld(g.intrinsics, g.camera, {centre.x, centre.y});
  const geometry::Vec3 origin = g.camera.CenterInWorld();
  const geometry::Vec3 x = origin - ray * (origin.z() / ray.z());
  ASSERT_LT(x.head<2>().norm(), 0.03);
  const geometry::Vec3 to_light = g.light_position - x;
  const geometry::Vec3 l = to_light.normalized(), v = (origin - x).normalized();
  const brdf::Rgb expected = scene.sample.brdf->Eval(l, v, geometry::Vec3::UnitZ()) *
                             g.light_intensity * l.z() / to_light.squaredNorm();
  const cv::Vec3f got = radiance.at<cv::Vec3f>(120, 160);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[2 - c], expected[c], 1e-4 * expected[c]) << c;
}

TEST(NbrdfSceneTest, ASampleCanNameAnNbrdfFile) {
  const fs::path file = brdf::NbrdfMaterialPath("steel");
  const Scene scene =
      LoadSceneString(DefaultSceneWith("{model: nbrdf, file: " + file.filename().string() + "}"),
                      "s.yaml", file.parent_path());
  EXPECT_EQ(scene.sample.brdf->Name(), "nbrdf(steel)");
}

TEST(NbrdfSceneTest, MistakesAreReportedWithTheSceneLine) {
  using ::testing::HasSubstr;
  // The error points at the sample's line of the default scene, wherever that is.
  const std::string text = DefaultSceneWith("{model: nbrdf, name: gold-paint}");
  const auto line =
      1 + std::count(text.begin(), text.begin() + text.find("name: gold-paint"), '\n');
  EXPECT_THAT(SceneError("{model: nbrdf, name: gold-paint}"),
              HasSubstr("scene.yaml:" + std::to_string(line) + ":"));
  EXPECT_THAT(SceneError("{model: nbrdf, name: gold-paint}"), HasSubstr("gold-metallic-paint"));
  EXPECT_THAT(SceneError("{model: nbrdf}"), HasSubstr("either 'name'"));
  EXPECT_THAT(SceneError("{model: nbrdf, name: brass, file: x.json}"), HasSubstr("not both"));
  EXPECT_THAT(SceneError("{model: nbrdf, file: missing.json}"), HasSubstr("missing.json"));
  EXPECT_THAT(SceneError("{model: nbrdf, name: brass, alpha: 1}"), HasSubstr("alpha"));
}

TEST(NbrdfSceneTest, ACaptureOfTheDefaultSceneWithAMeasuredSampleRenders) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_nbrdf_capture";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.yaml")
      << DefaultSceneWith("{model: nbrdf, name: blue-metallic-paint}");
  SimulateOptions options;
  options.scene = dir / "scene.yaml";
  options.output_dir = dir / "out";
  const SimulateSummary summary = Simulate(options);
  EXPECT_EQ(summary.positions, 6);
  EXPECT_EQ(summary.frames, 18);
  EXPECT_TRUE(fs::exists(dir / "out/photos/p05_e2.png"));
  EXPECT_TRUE(fs::exists(dir / "out/truth/p05.exr"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace brdfrig::sim
