// What the simulated camera delivers for one shot: a DNG that LibRaw decodes to the sensor's
// linear values in every channel, a JPEG that is the same image in 8-bit sRGB, and a signal
// that follows the exposure time, the ISO and the aperture.
#include "simcamera/shot_renderer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "reconstruct/raw_photo.h"
#include "sim_camera_fixture.h"

namespace brdfrig::simcamera {
namespace {

const geometry::AxisPositions kPose = {{"camera_arm", 0.4}, {"light_arm", -0.5}};

cv::Mat DecodeDng(const CapturedFile& file, const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(file.bytes.data()),
             static_cast<std::streamsize>(file.bytes.size()));
  cv::Mat image = reconstruct::ReadRawPhoto(path);
  std::filesystem::remove(path);
  return image;
}

TEST(ShotRenderer, DngDecodesThroughLibRawToTheSensorValuesInEveryChannel) {
  const sim::Scene scene = SmallTestScene();  // a coloured sample: f0 (0.9, 0.6, 0.35)
  ShotRenderer renderer(
      scene, [] { return kPose; }, 2);
  const ExposureSettings exposure{.exposure_s = 0.004, .iso = 100, .f_number = 8};
  const std::vector<CapturedFile> files = renderer.Shoot(exposure);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[1].extension, ".DNG");
  const cv::Mat raw = DecodeDng(files[1], "shot_renderer_test.dng");
  const cv::Mat sensor = sim::Simulator(scene).RenderCameraImage(kPose, 0.004, 1);
  ASSERT_EQ(raw.size(), sensor.size());
  int compared = 0;
  for (int y = 0; y < raw.rows; ++y) {
    for (int x = 0; x < raw.cols; ++x) {
      const auto r = raw.at<cv::Vec<std::uint16_t, 3>>(y, x);
      const auto s = sensor.at<cv::Vec3f>(y, x);
      for (int c = 0; c < 3; ++c) {
        if (s[c] >= 1) continue;  // clipped in the file
        EXPECT_NEAR(r[c] / 65535.0, s[c], 2e-4 + 0.002 * s[c]) << x << "," << y << " c" << c;
        ++compared;
      }
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(compared, raw.rows * raw.cols * 2);
}

TEST(ShotRenderer, JpegIsTheSameShotInEightBitSrgb) {
  const sim::Scene scene = SmallTestScene();
  ShotRenderer renderer(
      scene, [] { return kPose; }, 2);
  const std::vector<CapturedFile> files = renderer.Shoot({.exposure_s = 0.004});
  EXPECT_EQ(files[0].extension, ".JPG");
  const cv::Mat jpeg = cv::imdecode(files[0].bytes, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(jpeg.type(), CV_8UC3);
  const cv::Mat sensor = sim::Simulator(scene).RenderCameraImage(kPose, 0.004, 1);
  // Mid-grey in sRGB: a linear 0.2 encodes to 124.
  double worst = 0;
  for (int y = 0; y < jpeg.rows; ++y) {
    for (int x = 0; x < jpeg.cols; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp<double>(sensor.at<cv::Vec3f>(y, x)[c], 0, 1);
        const double srgb = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
        worst = std::max(worst, std::abs(jpeg.at<cv::Vec3b>(y, x)[c] - 255 * srgb));
      }
    }
  }
  EXPECT_LT(worst, 24) << "JPEG compression aside, the JPEG is the sRGB encoding of the sensor";
}

TEST(ShotRenderer, IsoAndApertureScaleTheSignalLikeExposureTime) {
  EXPECT_DOUBLE_EQ(EffectiveExposure({.exposure_s = 0.01, .iso = 100, .f_number = 8}), 0.01);
  EXPECT_DOUBLE_EQ(EffectiveExposure({.exposure_s = 0.01, .iso = 400, .f_number = 8}), 0.04);
  EXPECT_NEAR(EffectiveExposure({.exposure_s = 0.01, .iso = 100, .f_number = 5.6}), 0.0204, 1e-4);
}

TEST(ShotRenderer, EachShotRendersThePoseReadAtThatMoment) {
  const sim::Scene scene = SmallTestScene();
  geometry::AxisPositions pose = kPose;
  ShotRenderer renderer(
      scene, [&] { return pose; }, 2);
  const std::vector<std::uint8_t> first = renderer.Shoot({.exposure_s = 0.004})[1].bytes;
  pose["camera_arm"] = 0.6;
  const std::vector<std::uint8_t> moved = renderer.Shoot({.exposure_s = 0.004})[1].bytes;
  EXPECT_NE(first, moved);
  EXPECT_EQ(renderer.last_positions().at("camera_arm"), 0.6);
}

}  // namespace
}  // namespace brdfrig::simcamera
