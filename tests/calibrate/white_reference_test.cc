// The white reference measures the simulator's true paper albedo (0.75 against a tile of 0.95,
// 20 % vignetting corrected by the flat field calibrated from sim/scenes/flat_field.yaml)
// within 1 %, and refuses a cut-out that holds no reference tile.
#include "calibrate/white_reference.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "calibrate/flat_field.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "sim/devices.h"
#include "sim/scene.h"
#include "sim/world.h"

namespace brdfrig::calibrate {
namespace {

sim::Scene Scene(const std::string& file) {
  return sim::LoadScene(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/" + file);
}

std::vector<CalibrationPhoto> Photos(const sim::Scene& scene, int count, double exposure_s) {
  auto world = std::make_shared<sim::SimWorld>(scene);
  sim::SimCamera camera(world, {}, 0);
  std::vector<CalibrationPhoto> photos;
  for (int i = 0; i < count; ++i) {
    camera.SetExposure(exposure_s);
    const std::vector<rig::Frame> frames = camera.Capture();
    const std::vector<std::byte>& bytes = frames.front().bytes;
    const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8U,
                          const_cast<std::byte*>(bytes.data()));
    photos.push_back({"photo_" + std::to_string(i) + ".png",
                      cv::imdecode(encoded, cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH)});
  }
  return photos;
}

TEST(WhiteReferenceTest, PaperAlbedoIsMeasuredWithinOnePercentWithTheFlatField) {
  const sim::Scene scene = Scene("white_reference.yaml");
  const std::vector<CalibrationPhoto> photos = Photos(scene, 2, 1.0 / 30);
  WhiteReferenceOptions options;
  options.reference_albedo = 0.95;
  const WhiteReferenceResult uncorrected = CalibrateWhiteReference(photos, scene.rig, options);
  options.flat_field = CalibrateFlatField(Photos(Scene("flat_field.yaml"), 2, 1.0 / 30), {}).gain;
  const WhiteReferenceResult result = CalibrateWhiteReference(photos, scene.rig, options);
  const double truth = scene.rig.target.paper_albedo;
  std::printf("%s\nerror %+.3f %% with the flat field, %+.3f %% without\n",
              result.ToString().c_str(), 100 * (result.paper_albedo / truth - 1),
              100 * (uncorrected.paper_albedo / truth - 1));
  EXPECT_LT(std::abs(result.paper_albedo / truth - 1), 0.01);
}

TEST(WhiteReferenceTest, CutOutWithoutAReferenceTileIsRefused) {
  // A glossy sample in the cut-out instead of the tile, lit and seen from above.
  std::string yaml =
      ReadFileToString(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/white_reference.yaml");
  const std::string tile = "{model: lambert, albedo: 0.95}";
  ASSERT_NE(yaml.find(tile), std::string::npos);
  yaml.replace(yaml.find(tile), tile.size(), "{model: ggx, alpha: 0.1, f0: 0.9, diffuse: 0.1}");
  const sim::Scene scene = sim::LoadSceneString(yaml, "glossy.yaml");
  WhiteReferenceOptions options;
  options.reference_albedo = 0.95;
  try {
    CalibrateWhiteReference(Photos(scene, 1, 0.002), scene.rig, options);
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("reference tile not found"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace brdfrig::calibrate
