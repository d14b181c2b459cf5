// The flat field recovers the simulator's vignetting (sim/scenes/flat_field.yaml: 20 % towards
// the corners, default sensor noise) within 1 %, and refuses overexposed, underexposed and
// non-uniform photos.
#include "calibrate/flat_field.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "sim/devices.h"
#include "sim/scene.h"
#include "sim/world.h"
#include "tests/calibrate/simulated_board_photos.h"

namespace brdfrig::calibrate {
namespace {

// Photos of the scene at the arms' rest through the simulated camera, each a new frame.
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
    photos.push_back({"flat_" + std::to_string(i) + ".png",
                      cv::imdecode(encoded, cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH)});
  }
  return photos;
}

std::string Refusal(const std::vector<CalibrationPhoto>& photos) {
  try {
    CalibrateFlatField(photos, {});
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

sim::Scene FlatScene() {
  return sim::LoadScene(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/flat_field.yaml");
}

TEST(FlatFieldTest, GainMapIsTheSimulatedVignettingWithinOnePercent) {
  const sim::Scene scene = FlatScene();
  const FlatFieldResult result = CalibrateFlatField(Photos(scene, 2, 1.0 / 30), {});
  // The truth: the scene's polynomial about the true principal point, scaled to mean 1 too.
  const sim::VignettingEffect& v = *scene.effects.vignetting;
  const geometry::Intrinsics& k = scene.rig.intrinsics;
  cv::Mat truth(result.gain.size(), CV_32F);
  const double half_diagonal2 = 0.25 * (k.width * k.width + k.height * k.height);
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      const double r2 = ((x - k.cx) * (x - k.cx) + (y - k.cy) * (y - k.cy)) / half_diagonal2;
      truth.at<float>(y, x) = static_cast<float>(1 + v.a1 * r2 + v.a2 * r2 * r2);
    }
  }
  truth /= cv::mean(truth)[0];
  cv::Mat relative = result.gain / truth - 1;
  double lo = 0, hi = 0;
  cv::minMaxLoc(relative, &lo, &hi);
  double truth_lo = 0, truth_hi = 0;
  cv::minMaxLoc(truth, &truth_lo, &truth_hi);
  std::printf(
      "%s\nworst error against the simulated vignetting: %+.3f %% .. %+.3f %% "
      "(vignetting %.1f %%)\n",
      result.ToString().c_str(), 100 * lo, 100 * hi, 100 * (1 - truth_lo / truth_hi));
  EXPECT_LT(std::max(-lo, hi), 0.01);
  EXPECT_GT(1 - truth_lo / truth_hi, 0.15) << "the scene must vignette for this to mean much";
}

TEST(FlatFieldTest, OverexposedUnderexposedAndPatternedPhotosAreRefused) {
  const sim::Scene scene = FlatScene();
  const std::vector<CalibrationPhoto> bright = Photos(scene, 1, 0.25);
  EXPECT_NE(Refusal(bright).find("overexposed"), std::string::npos) << Refusal(bright);
  std::vector<CalibrationPhoto> dark = Photos(scene, 1, 1.0 / 30);
  dark[0].image /= 40;
  EXPECT_NE(Refusal(dark).find("underexposed"), std::string::npos) << Refusal(dark);
  // A printed board is not a uniform card.
  const sim::Scene board = testing::HalfResolution(sim::LoadScene(testing::ChArUcoScenePath()));
  const std::vector<CalibrationPhoto> patterned = testing::SimulatedBoardPhotos(board, {0});
  EXPECT_NE(Refusal(patterned).find("not uniform"), std::string::npos) << Refusal(patterned);
}

}  // namespace
}  // namespace brdfrig::calibrate
