// Image synthesis recovers what was put in: closed-form Lambertian radiance, highlights where
// the law of reflection puts them, anti-aliased edges, determinism, and truth files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "sim/image_io.h"
#include "sim/simulator.h"
#include "test_scene.h"

namespace brdfrig::sim {
namespace {

using testing::TestScene;

constexpr double kDegree = M_PI / 180.0;

// World point seen by pixel (u, v) of the test scene's camera at rest (derived by hand, not
// with rig code): straight down from 0.5 m, f = 400 px, principal point (160, 120).
geometry::Vec3 PointAtRest(double u, double v) {
  return {(u - 160.0) / 400.0 * 0.5, -(v - 120.0) / 400.0 * 0.5, 0.0};
}

double LambertRadiance(double albedo, const geometry::Vec3& light, double intensity,
                       const geometry::Vec3& p) {
  const geometry::Vec3 to_light = light - p;
  const double d = to_light.norm();
  return albedo / M_PI * intensity * (to_light.z() / d) / (d * d);
}

bool OnPaper(const geometry::Vec3& p, double margin) {
  const double ax = std::abs(p.x()), ay = std::abs(p.y());
  const bool in_cutout = ax < 0.05 + margin && ay < 0.04 + margin;
  return !in_cutout && ax < 0.15 - margin && ay < 0.15 - margin;
}

TEST(SynthesisTest, LambertianPaperMatchesClosedFormEverywhere) {
  const Simulator simulator(TestScene());
  const cv::Mat radiance = simulator.RenderRadiance({});
  const geometry::Vec3 light(0.05, 0.1, 0.6);
  int checked = 0;
  for (int v = 0; v < radiance.rows; ++v) {
    for (int u = 0; u < radiance.cols; ++u) {
      const geometry::Vec3 p = PointAtRest(u, v);
      if (!OnPaper(p, 0.002)) continue;
      const double expected = LambertRadiance(0.7, light, 2.0, p);
      const cv::Vec3f px = radiance.at<cv::Vec3f>(v, u);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(px[c], expected, 1e-5 * expected) << u << "," << v;
      ++checked;
    }
  }
  EXPECT_GT(checked, 30000);
}

TEST(SynthesisTest, IdealCameraIsRadianceTimesExposureTimesGain) {
  const Simulator simulator(TestScene());
  const cv::Mat radiance = simulator.RenderRadiance({});
  const cv::Mat image = simulator.Expose(radiance, 0.01, 1);
  const double scale = 0.01 * 10;  // exposure × sensor.gain
  EXPECT_LT(cv::norm(image, radiance * scale, cv::NORM_INF),
            1e-6 * cv::norm(radiance, cv::NORM_INF));
  // Linear and unclipped: a long exposure is allowed to exceed full scale.
  const cv::Mat bright = simulator.Expose(radiance, 100.0, 1);
  double max_value = 0;
  cv::minMaxLoc(bright.reshape(1), nullptr, &max_value);
  EXPECT_GT(max_value, 1.0);
}

TEST(SynthesisTest, BackgroundTableIsLambertianWithItsOwnAlbedo) {
  const Simulator simulator(TestScene());
  const cv::Mat radiance = simulator.RenderRadiance({});
  const int u = 5, v = 120;  // x = −0.194 m: outside the 0.3 m paper
  const double expected = LambertRadiance(0.05, {0.05, 0.1, 0.6}, 2.0, PointAtRest(u, v));
  EXPECT_NEAR(radiance.at<cv::Vec3f>(v, u)[1], expected, 1e-5 * expected);
}

TEST(SynthesisTest, HighlightLandsWhereTheLawOfReflectionPutsIt) {
  // A near-mirror sample: the brightest pixel is the mirror point of camera and light.
  const Simulator simulator(TestScene("", "{model: ggx, alpha: 0.02, f0: 1.0}"));
  const geometry::AxisPositions positions = {{"camera_arm", 30 * kDegree},
                                             {"light_arm", -20 * kDegree}};
  const TrueGeometry g = simulator.GeometryAt(positions);
  const geometry::Vec3 c = g.camera.CenterInWorld();
  const geometry::Vec3 mirrored_light(g.light_position.x(), g.light_position.y(),
                                      -g.light_position.z());
  const geometry::Vec3 mirror_point =
      c + c.z() / (c.z() + g.light_position.z()) * (mirrored_light - c);
  ASSERT_LT(std::abs(mirror_point.x()), 0.05);
  ASSERT_LT(std::abs(mirror_point.y()), 0.04);
  Eigen::Vector2d expected;
  ASSERT_TRUE(geometry::ProjectToPixel(g.intrinsics, g.camera, mirror_point, &expected));

  const cv::Mat radiance = simulator.RenderRadiance(positions);
  cv::Mat green;
  cv::extractChannel(radiance, green, 1);
  cv::Point brightest;
  cv::minMaxLoc(green, nullptr, nullptr, nullptr, &brightest);
  EXPECT_NEAR(brightest.x, expected.x(), 1.5);
  EXPECT_NEAR(brightest.y, expected.y(), 1.5);
  // And it is a highlight: far brighter than the paper.
  EXPECT_GT(green.at<float>(brightest), 100 * green.at<float>(10, 160));
}

TEST(SynthesisTest, SupersamplingAntiAliasesEdgesAndLeavesInteriorsUntouched) {
  Scene scene = TestScene();
  const Simulator sharp(scene);
  scene.render.supersampling = 4;
  const Simulator smooth(scene);
  const cv::Mat a = sharp.RenderRadiance({});
  const cv::Mat b = smooth.RenderRadiance({});
  // The cut-out's left edge x = −0.05 m is at u = 120 exactly: pixel 120 is half paper
  // (u < 120), half sample.
  const int v = 120;
  const cv::Vec3f outside = a.at<cv::Vec3f>(v, 119), inside = a.at<cv::Vec3f>(v, 121);
  const cv::Vec3f edge = b.at<cv::Vec3f>(v, 120);
  for (int ch = 0; ch < 3; ++ch) {
    ASSERT_GT(std::abs(inside[ch] - outside[ch]), 0.01 * outside[ch]);
    const double mean = 0.5 * (inside[ch] + outside[ch]);
    EXPECT_NEAR(edge[ch], mean, 0.05 * std::abs(inside[ch] - outside[ch]));
  }
  // Pixels away from every edge are the same bits with or without supersampling.
  EXPECT_EQ(a.at<cv::Vec3f>(120, 160), b.at<cv::Vec3f>(120, 160));
  EXPECT_EQ(a.at<cv::Vec3f>(20, 160), b.at<cv::Vec3f>(20, 160));
  // Only edge pixels change: the cut-out and paper outlines, a few per row.
  const cv::Mat changed = cv::Mat(a != b).reshape(1);
  EXPECT_LT(cv::countNonZero(changed), 3 * 4 * (320 + 240) * 2);
  EXPECT_GT(cv::countNonZero(changed), 3 * 2 * 240);
}

TEST(SynthesisTest, SameSeedGivesIdenticalBytesWhateverTheThreadCount) {
  const Simulator simulator(TestScene(R"(effects:
  - {type: shot_noise, full_well: 500}
  - {type: read_noise, sigma: 0.01}
)"));
  RenderOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const geometry::AxisPositions positions = {{"camera_arm", 10 * kDegree}};
  const cv::Mat a = simulator.RenderCameraImage(positions, 0.01, 5, one);
  const cv::Mat b = simulator.RenderCameraImage(positions, 0.01, 5, three);
  EXPECT_EQ(simulator.EncodePhoto(a), simulator.EncodePhoto(b));
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  // Another frame has other noise.
  const cv::Mat c = simulator.RenderCameraImage(positions, 0.01, 6, one);
  EXPECT_GT(cv::norm(a, c, cv::NORM_INF), 0.0);
}

TEST(SynthesisTest, PhotoEncodingRoundsToSixteenBitsAndClips) {
  const Simulator simulator(TestScene());
  const cv::Mat image = simulator.RenderCameraImage({}, 0.01, 1);
  const std::vector<std::byte> bytes = simulator.EncodePhoto(image);
  const cv::Mat decoded = cv::imdecode(
      cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::byte*>(bytes.data())),
      cv::IMREAD_UNCHANGED);
  ASSERT_EQ(decoded.type(), CV_16UC3);
  ASSERT_EQ(decoded.size(), image.size());
  for (int v = 0; v < image.rows; v += 7) {
    for (int u = 0; u < image.cols; u += 5) {
      for (int c = 0; c < 3; ++c) {
        const double expected =
            std::round(std::clamp<double>(image.at<cv::Vec3f>(v, u)[c], 0, 1) * 65535);
        ASSERT_EQ(decoded.at<cv::Vec3w>(v, u)[c], expected);
      }
    }
  }
}

TEST(SynthesisTest, SensorFormatChoosesTiff16OrJpeg8) {
  Scene scene = TestScene();
  scene.sensor.format = PhotoFormat::kTiff16;
  const Simulator tiff(scene);
  const cv::Mat image = tiff.RenderCameraImage({}, 0.01, 1);
  auto decode = [](const std::vector<std::byte>& bytes) {
    return cv::imdecode(
        cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::byte*>(bytes.data())),
        cv::IMREAD_UNCHANGED);
  };
  const cv::Mat t = decode(tiff.EncodePhoto(image));
  ASSERT_EQ(t.type(), CV_16UC3);
  EXPECT_EQ(t.at<cv::Vec3w>(120, 160)[1],
            std::round(std::clamp<double>(image.at<cv::Vec3f>(120, 160)[1], 0, 1) * 65535));
  scene.sensor.format = PhotoFormat::kJpeg8;
  const Simulator jpeg(scene);
  const std::vector<std::byte> bytes = jpeg.EncodePhoto(image);
  ASSERT_GT(bytes.size(), 2u);
  EXPECT_EQ(bytes[0], std::byte{0xFF});
  EXPECT_EQ(bytes[1], std::byte{0xD8});
  const cv::Mat j = decode(bytes);
  ASSERT_EQ(j.type(), CV_8UC3);
  // Lossy, but close on smooth paper.
  EXPECT_NEAR(j.at<cv::Vec3b>(20, 160)[1], image.at<cv::Vec3f>(20, 160)[1] * 255, 2.0);
}

TEST(SynthesisTest, TruthFilesHoldRadianceAndGeometry) {
  const Simulator simulator(TestScene());
  const geometry::AxisPositions positions = {{"camera_arm", 20 * kDegree}};
  const cv::Mat radiance = simulator.RenderRadiance(positions);
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_sim_truth_test";
  std::filesystem::create_directories(dir);
  WriteRadianceExr(dir / "r.exr", radiance);
  const cv::Mat back = ReadRadianceExr(dir / "r.exr");
  EXPECT_EQ(cv::norm(radiance, back, cv::NORM_INF), 0.0);
  WriteTrueGeometry(dir / "g.json", simulator.GeometryAt(positions));
  std::ifstream in(dir / "g.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_NEAR(j["axis_positions_rad"]["camera_arm"].get<double>(), 20 * kDegree, 1e-12);
  const geometry::Vec3 center = simulator.GeometryAt(positions).camera.CenterInWorld();
  EXPECT_NEAR(j["camera_center_in_world"][1].get<double>(), center.y(), 1e-12);
  EXPECT_NEAR(center.y(), -0.5 * std::sin(20 * kDegree), 1e-12);
  EXPECT_EQ(j["intrinsics"]["width"].get<int>(), 320);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace brdfrig::sim
