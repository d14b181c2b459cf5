// The renderer and the simulator must agree on a capture's radiance: evaluation compares photos
// with renderings, so any disagreement here would show up as a fitting error.
#include "render/capture_view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/gl_context.h"
#include "sim/scene.h"
#include "sim/simulator.h"

namespace brdfrig::render {
namespace {

sim::Scene SmallIdealScene() {
  sim::Scene scene =
      sim::LoadScene(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/ggx.yaml").Ideal();
  geometry::Intrinsics& k = scene.rig.intrinsics;
  const double scale = 400.0 / k.width;
  k.width = 400;
  k.height = static_cast<int>(std::lround(k.height * scale));
  k.fx *= scale;
  k.fy *= scale;
  k.cx = k.width / 2.0;
  k.cy = k.height / 2.0;
  return scene;
}

TEST(CaptureViewTest, RendererMatchesSimulatorRadianceAtEveryCapturePosition) {
  auto context = CreateHeadlessContext();
  const sim::Scene scene = SmallIdealScene();
  const sim::Simulator simulator(scene);
  for (const geometry::AxisPositions& positions : scene.capture.positions) {
    const sim::TrueGeometry truth = simulator.GeometryAt(positions);
    const cv::Mat expected = simulator.RenderRadiance(positions);
    CaptureView capture;
    capture.target = scene.rig.target;
    capture.background_albedo = scene.background_albedo;
    capture.view.intrinsics = truth.intrinsics;
    capture.view.pose = truth.camera;
    capture.light.position = truth.light_position;
    capture.light.intensity = brdf::Rgb::Constant(truth.light_intensity);
    capture.supersampling = scene.render.supersampling;
    const cv::Mat rendered = RenderCaptureView(capture, *scene.sample.brdf);
    ASSERT_EQ(rendered.size(), expected.size());

    std::vector<double> rel;
    double sum_expected = 0, sum_rendered = 0;
    for (int y = 0; y < expected.rows; ++y) {
      for (int x = 0; x < expected.cols; ++x) {
        const cv::Vec3f e = expected.at<cv::Vec3f>(y, x), r = rendered.at<cv::Vec3f>(y, x);
        for (int c = 0; c < 3; ++c) {
          sum_expected += e[c];
          sum_rendered += r[c];
          rel.push_back(std::abs(e[c] - r[c]) / std::max(std::abs(e[c]), 1e-6f));
        }
      }
    }
    std::sort(rel.begin(), rel.end());
    // Both supersample on the same sub-pixel grid (the simulator only at edges, where it
    // matters; the box filter of a smooth interior differs at second order).
    EXPECT_LT(rel[rel.size() / 2], 1e-4);
    EXPECT_LT(rel[rel.size() * 99 / 100], 3e-3);
    EXPECT_NEAR(sum_rendered / sum_expected, 1.0, 1e-3);
  }
}

}  // namespace
}  // namespace brdfrig::render
