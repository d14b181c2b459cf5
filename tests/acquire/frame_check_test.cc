// The per-frame check: decoding, size, all-black frames and the saturated fraction.
#include "acquire/frame_check.h"

#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace brdfrig::acquire {
namespace {

std::vector<std::byte> Encode(const cv::Mat& image, const std::string& ext) {
  std::vector<uchar> buffer;
  cv::imencode(ext, image, buffer);
  std::vector<std::byte> bytes(buffer.size());
  std::memcpy(bytes.data(), buffer.data(), buffer.size());
  return bytes;
}

TEST(FrameCheckTest, SaturatedFractionCountsPixelsAtFullScale) {
  cv::Mat image(10, 20, CV_16UC1, cv::Scalar(30000));
  image(cv::Rect(0, 0, 5, 10)).setTo(65535);  // a quarter of the frame clipped
  FrameCheckOptions options;
  options.expected_width = 20;
  options.expected_height = 10;
  cv::Mat levels;
  const FrameCheck check = CheckFrame(Encode(image, ".png"), "x.png", options, &levels);
  EXPECT_TRUE(check.ok) << check.problem;
  EXPECT_TRUE(check.decoded);
  EXPECT_NEAR(check.saturated_fraction, 0.25, 1e-12);
  EXPECT_NEAR(check.max_level, 1.0, 1e-6);
  EXPECT_NEAR(levels.at<float>(5, 10), 30000.0 / 65535, 1e-6);
}

TEST(FrameCheckTest, ColourFramesAreSaturatedWhereAnyChannelIs) {
  cv::Mat image(4, 4, CV_8UC3, cv::Scalar(10, 20, 30));
  image.at<cv::Vec3b>(0, 0) = {255, 0, 0};
  const FrameCheck check = CheckFrame(Encode(image, ".png"), "x.PNG", {}, nullptr);
  EXPECT_TRUE(check.decoded);
  EXPECT_GT(check.saturated_fraction, 0);
}

TEST(FrameCheckTest, WrongSizeBlackUndecodableAndEmptyAreRejected) {
  FrameCheckOptions options;
  options.expected_width = 64;
  options.expected_height = 48;
  const cv::Mat small(24, 32, CV_16UC1, cv::Scalar(1000));
  EXPECT_NE(CheckFrame(Encode(small, ".png"), "a.png", options).problem.find("expected 64x48"),
            std::string::npos);
  const cv::Mat black(48, 64, CV_16UC1, cv::Scalar(0));
  EXPECT_NE(CheckFrame(Encode(black, ".png"), "b.png", options).problem.find("all black"),
            std::string::npos);
  const std::vector<std::byte> garbage(100, std::byte{7});
  EXPECT_FALSE(CheckFrame(garbage, "c.png", options).ok);
  EXPECT_FALSE(CheckFrame({}, "d.png", options).ok);
  // RAW files are not decoded here: accepted unchecked (the reconstruction decodes them).
  const FrameCheck raw = CheckFrame(garbage, "e.NEF", options);
  EXPECT_TRUE(raw.ok);
  EXPECT_FALSE(raw.decoded);
}

// Bytes of another format named .png never reach OpenCV's decoders (fuzz_photo found one that
// made GDCM's DICOM reader abort the process; common/photo_signature.h).
TEST(FrameCheckTest, AFrameOfAnotherFormatIsRejectedBeforeDecoding) {
  std::string text = "=PNG\r\n\x1a\n";
  text += std::string(120, '\0') + "DICM" + std::string(64, '\x01');
  std::vector<std::byte> bytes(text.size());
  std::memcpy(bytes.data(), text.data(), text.size());
  const FrameCheck check = CheckFrame(bytes, "p00_e0.png", {});
  EXPECT_FALSE(check.ok);
  EXPECT_FALSE(check.decoded);
  EXPECT_EQ(check.problem, "not a PNG, JPEG or TIFF image");
}

}  // namespace
}  // namespace brdfrig::acquire
